# Writes 10^6 power-cosine samples (n = 10) as CSV "x,y,z" lines: stands for any language's sampler.
import numpy as np

n = 10.0
rng = np.random.default_rng(1)
u = rng.random((1000000, 2))
z = u[:, 0] ** (1.0 / (n + 1.0))
r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
phi = 2.0 * np.pi * u[:, 1]
np.savetxt("samples.csv", np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1),
           fmt="%.9g", delimiter=",", header="x,y,z", comments="")
