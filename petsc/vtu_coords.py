"""Node coordinates of a ctc VTU in natural node order (its `node` array),
saved as an (n, 3) .npy for petsc/gamg_probe.py (needs meshio):
    python3 petsc/vtu_coords.py RUN/inc_0001_p0.vtu OUT/x.npy
"""
import sys

import meshio
import numpy as np

mesh = meshio.read(sys.argv[1])
node = np.asarray(mesh.point_data["node"]).astype(int).ravel()
X = np.zeros((node.max() + 1, 3))
X[node] = mesh.points
np.save(sys.argv[2], X)
print(X.shape)
