"""python3 -m wideray: the version, the instruction set in use, and a check that rays hit a mesh."""
import sys

import numpy as np

import wideray


def main():
    vertices = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=np.float32)
    scene = wideray.Scene(vertices, np.array([[0, 1, 2]]))
    origins = np.array([[0, 0, -1], [5, 5, -1]], dtype=np.float32)
    t, prim_id, _, _ = scene.intersect(origins, np.array([[0, 0, 1]] * 2, dtype=np.float32))
    print(f"wideray {wideray.__version__}, {wideray.best_isa()} kernels; {scene.description}")
    ok = t[0] == 1.0 and prim_id[0] == 0 and prim_id[1] == -1
    print("a ray hit the triangle at t = 1 and one missed it" if ok else f"unexpected hits: t {t}, prim_id {prim_id}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
