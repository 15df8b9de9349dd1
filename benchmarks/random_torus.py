#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# Area-uniform random samples of a torus (R=1, r=0.35), jitter 1e-5 of the diagonal,
# written as a binary PCD. Usage: random_torus.py N OUT.pcd [SEED]
import sys, numpy as np
n = int(sys.argv[1]); out = sys.argv[2]; seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
R, r = 1.0, 0.35
rng = np.random.default_rng(seed)
pts = []
have = 0
while have < n:
    m = int((n - have) * 1.6) + 1000
    u = rng.uniform(0, 2*np.pi, m); v = rng.uniform(0, 2*np.pi, m)
    keep = rng.uniform(0, 1, m) < (R + r*np.cos(v)) / (R + r)   # area element
    u, v = u[keep], v[keep]
    p = np.stack([(R + r*np.cos(v))*np.cos(u), (R + r*np.cos(v))*np.sin(u), r*np.sin(v)], 1)
    pts.append(p); have += len(p)
p = np.concatenate(pts)[:n]  # rows in the order drawn: the classes sort them spatially
diag = np.linalg.norm(p.max(0) - p.min(0))
p += rng.uniform(-1e-5, 1e-5, p.shape) * diag
p = p.astype(np.float32)
with open(out, 'wb') as f:
    f.write(("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH %d\nHEIGHT 1\n"
             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA binary\n" % (n, n)).encode())
    f.write(p.tobytes())
