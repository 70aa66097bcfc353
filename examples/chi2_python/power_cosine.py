# Tests a NumPy power-cosine sampler with ptlab's chi-square lab (PYTHONPATH=build/python).
import sys

import numpy as np
import ptlab

N = 10.0  # the lobe p(w) = (n+1)/(2 pi) cos^n(theta) on the upper hemisphere


def sample_power_cosine(u):  # (M, 2) uniforms -> (M, 3) unit vectors
    z = u[:, 0] ** (1.0 / (N + 1.0))
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    phi = 2.0 * np.pi * u[:, 1]
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def power_cosine_pdf(w):  # (M, 3) unit vectors -> (M,) densities per steradian
    return np.where(w[:, 2] > 0, (N + 1.0) / (2.0 * np.pi) * np.abs(w[:, 2]) ** N, 0.0)


if __name__ == "__main__":
    result = ptlab.chi2_test("hemisphere", sample_power_cosine, power_cosine_pdf,
                             samples=1000000, res=51, alpha=0.01, images="out/chi2",
                             name="power_cosine_n10")
    print(result)  # PASS/FAIL, chi2, dof, p, alpha', pdf integral
    sys.exit(0 if result.passed else 1)
