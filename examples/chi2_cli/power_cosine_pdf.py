# Answers ptlab's pdf queries: reads "x y z" lines from stdin, prints one density per line.
import sys

import numpy as np

n = 10.0
w = np.array(sys.stdin.read().split(), dtype=np.float64).reshape(-1, 3)
pdf = np.where(w[:, 2] > 0, (n + 1.0) / (2.0 * np.pi) * np.abs(w[:, 2]) ** n, 0.0)
sys.stdout.write("".join(f"{v!r}\n" for v in pdf.tolist()))
