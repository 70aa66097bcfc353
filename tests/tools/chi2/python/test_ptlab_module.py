# The `ptlab` Python module: docs/chi2.md's example, broken variants, same chi2 as `chi2 check`, errors.
import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import ptlab

SOURCE = pathlib.Path(os.environ["PTLAB_SOURCE_DIR"])
CHI2 = os.environ["PTLAB_CHI2"]
sys.path.insert(0, str(SOURCE / "examples" / "chi2_python"))
import power_cosine  # noqa: E402  (docs/chi2.md's example, imported as written)

PDF_PROGRAM = f"{sys.executable} {SOURCE / 'examples' / 'chi2_cli' / 'power_cosine_pdf.py'}"
FAST = dict(samples=200000, res=25)


def test_readme_example_runs_as_written(tmp_path):
    run = subprocess.run([sys.executable, SOURCE / "examples" / "chi2_python" / "power_cosine.py"],
                         cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.startswith("PASS")
    assert (tmp_path / "out" / "chi2" / "power_cosine_n10.png").stat().st_size > 0


def test_broken_variants_fail():
    half = ptlab.chi2_test("hemisphere", power_cosine.sample_power_cosine,
                           lambda w: 0.5 * power_cosine.power_cosine_pdf(w), **FAST)
    assert half.passed is False
    assert abs(half.pdf_integral - 0.5) < 1e-4

    def pdf_n11(w):
        return np.where(w[:, 2] > 0, 12.0 / (2.0 * np.pi) * np.abs(w[:, 2]) ** 11, 0.0)

    other = ptlab.chi2_test("hemisphere", power_cosine.sample_power_cosine, pdf_n11, **FAST)
    assert other.passed is False
    assert other.p_value < 1e-6


def test_power_of_an_outside_sampler():
    # The power report on a sampler outside ptlab's tree: the README's lobe at 10^6 samples
    # catches a 2 % smooth error; at 4 % of the samples it does not (the estimate scales).
    full = ptlab.chi2_test("hemisphere", power_cosine.sample_power_cosine,
                           power_cosine.power_cosine_pdf, samples=1000000, power=True)
    assert full.passed
    assert 0.005 < full.power_epsilon < 0.02
    assert full.power_at_2 >= 0.95
    assert full.power_report.startswith("detects a ")
    few = ptlab.chi2_test("hemisphere", power_cosine.sample_power_cosine,
                          power_cosine.power_cosine_pdf, samples=40000, power=True)
    assert few.power_epsilon > 0.04
    assert few.power_samples_for_2 > 40000
    assert np.isnan(ptlab.chi2_test("hemisphere", power_cosine.sample_power_cosine,
                                    power_cosine.power_cosine_pdf, **FAST).power_epsilon)


def test_same_chi2_as_the_cli_on_the_same_samples(tmp_path):
    drawn = []

    def sample(u):
        p = power_cosine.sample_power_cosine(u)
        drawn.append(np.asarray(p, dtype=np.float32))
        return p

    r = ptlab.chi2_test("hemisphere", sample, power_cosine.power_cosine_pdf, **FAST)
    assert r.passed is True
    points = np.concatenate(drawn)
    assert points.shape == (200000, 3)
    # The same points given as an array: bit-identical result.
    r2 = ptlab.chi2_test("hemisphere", points, power_cosine.power_cosine_pdf, **FAST)
    assert (r2.chi2, r2.p_value, r2.dof) == (r.chi2, r.p_value, r.dof)
    # Through chi2 check with docs/chi2.md's pdf program (the same formula in float64).
    points.astype("<f4").tofile(tmp_path / "samples.f32")
    run = subprocess.run([CHI2, "check", "--domain", "hemisphere", "--dims", "3", "--samples",
                          str(tmp_path / "samples.f32"), "--res", "25", "--json",
                          "--pdf-cmd", PDF_PROGRAM], capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    cli = json.loads(run.stdout)
    assert (cli["chi2"], cli["p_value"], cli["dof"], cli["passed"]) == (r.chi2, r.p_value, r.dof, True)


def test_t_test():
    v = np.arange(1000) % 10 * 0.1
    assert ptlab.t_test(v, reference=0.45).passed is True
    assert ptlab.t_test(v, reference=0.5).passed is False
    assert ptlab.t_test(v, other=v + 0.05).passed is False
    with pytest.raises(ValueError, match="either reference= .* or other="):
        ptlab.t_test(v)
    with pytest.raises(ValueError, match="value 3 is nan"):
        ptlab.t_test(np.array([1.0, 2.0, 3.0, np.nan]), reference=1.0)


SMALL = dict(samples=2000, res=6)
pdf = power_cosine.power_cosine_pdf
sample = power_cosine.sample_power_cosine


@pytest.mark.parametrize("bad_sample, message", [
    (lambda u: sample(u)[:, :2], r"sample\(u\) has shape \(2000, 2\), expected \(2000, 3\)"),
    (lambda u: sample(u)[:-1], r"sample\(u\) has shape \(1999, 3\), expected \(2000, 3\)"),
    (lambda u: None, r"sample\(u\) has shape \(\), expected \(2000, 3\)"),
    (lambda u: "text", r"sample\(u\) is not a float array: expected shape \(2000, 3\)"),
    (lambda u: np.where(np.arange(2000)[:, None] == 5, np.nan, sample(u)),
     r"sample 5 is \(nan, nan, nan\): not finite"),
    (lambda u: -sample(u), r"sample 0 is .*: outside the domain hemisphere"),
])
def test_bad_samples_raise_value_error(bad_sample, message):
    with pytest.raises(ValueError, match=message):
        ptlab.chi2_test("hemisphere", bad_sample, pdf, **SMALL)


def test_bad_pdfs_and_arguments():
    with pytest.raises(ValueError, match=r"pdf\(points\) returned shape \(\d+, 3\) for \d+ points"):
        ptlab.chi2_test("hemisphere", sample, lambda w: w, **SMALL)

    def dies(w):
        raise ZeroDivisionError("my pdf broke")

    with pytest.raises(ZeroDivisionError, match="my pdf broke"):
        ptlab.chi2_test("hemisphere", sample, dies, **SMALL)
    with pytest.raises(ValueError, match=r"unknown domain \"cube\""):
        ptlab.chi2_test("cube", sample, pdf, **SMALL)
    with pytest.raises(ValueError, match=r"the samples has shape \(0, 3\)|no samples given"):
        ptlab.chi2_test("hemisphere", np.zeros((0, 3), np.float32), pdf, **SMALL)
    with pytest.raises(ValueError, match=r"the samples has shape \(10,\), expected \(N, 3\)"):
        ptlab.chi2_test("hemisphere", np.zeros(10), pdf, **SMALL)
    with pytest.raises(ValueError, match=r"alpha must be in \(0, 1\)"):
        ptlab.chi2_test("hemisphere", sample, pdf, alpha=2.0, **SMALL)
