# Answers ptlab's pdf queries: reads "x y z" lines from stdin, prints one density per line.
import sys

import numpy as np

n = 10.0
w = np.loadtxt(sys.stdin, ndmin=2)
pdf = np.where(w[:, 2] > 0, (n + 1.0) / (2.0 * np.pi) * np.abs(w[:, 2]) ** n, 0.0)
np.savetxt(sys.stdout, pdf, fmt="%.17g")
