"""hhneck-xdmf read by VTK's own XDMF reader (the one ParaView uses): the
file of the short deck's result loads without an error line, every step
holds the three grids, and the 'surfaces' grid has the bodies' triangle
meshes with points and cells.

Independent truth: the head's surface vertices VTK returns at the last
step, taken back into the head's frame with /bodies/position and
/bodies/rotation of the result file, lie on the uniform ellipsoid whose
semi-axes follow from /model/mass and /model/inertia by a_i^2 = 5 (I_j +
I_k - I_i) / (2 m) in the principal axes; each vertebra's 8 box corners are
at the body frame's position plus the rotated corner offsets (a box: its
12 edges come in 3 groups of 4 equal lengths)."""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import hhneck_module

try:
    import vtk  # noqa: F401
    HAVE_VTK = True
except ImportError:
    HAVE_VTK = False

pytestmark = pytest.mark.skipif(not HAVE_VTK, reason="VTK's Python package is not installed "
                                                     "(pip install vtk; tools/setup.sh installs it)")

# run in a subprocess: VTK prints its errors from C++ on the process's stderr
READER = r"""
import json, sys, vtk
r = vtk.vtkXdmfReader()
r.SetFileName(sys.argv[1])
r.UpdateInformation()
times = list(r.GetOutputInformation(0).Get(vtk.vtkStreamingDemandDrivenPipeline.TIME_STEPS()) or [])
r.UpdateTimeStep(times[-1])
out = r.GetOutputDataObject(0)
blocks = {}
it = out.NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    d = it.GetCurrentDataObject()
    name = it.GetCurrentMetaData().Get(vtk.vtkCompositeDataSet.NAME()).split("[")[0]   # "surfaces[4]" at step 4
    pts = d.GetPoints()
    body = d.GetCellData().GetArray("body")
    cells = []
    for c in range(d.GetNumberOfCells()):
        ids = d.GetCell(c).GetPointIds()
        cells.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    blocks[name] = {"points": [list(pts.GetPoint(k)) for k in range(d.GetNumberOfPoints())] if pts else [],
                    "cells": cells, "types": sorted({d.GetCellType(c) for c in range(d.GetNumberOfCells())}),
                    "body": [body.GetValue(c) for c in range(body.GetNumberOfTuples())] if body else []}
    it.GoToNextItem()
print(json.dumps({"times": times, "blocks": blocks}))
"""


@pytest.fixture(scope="module")
def vtk_read(result_file, tmp_path_factory):
    """(what VTK read at the last step, its stderr, the result file copy)."""
    d = tmp_path_factory.mktemp("xdmf")
    h5 = str(d / "short.h5")
    shutil.copy(result_file, h5)
    r = hhneck_module("tools.xdmf", h5, "--every", "0.005")
    assert r.returncode == 0, r.stderr
    v = subprocess.run([sys.executable, "-c", READER, str(d / "short.xmf")], capture_output=True, text=True,
                       cwd=str(d))
    assert v.returncode == 0, v.stderr[-2000:]
    return json.loads(v.stdout.strip().splitlines()[-1]), v.stderr, h5


def test_vtk_reads_the_file_without_an_error_line(vtk_read):
    data, err, _ = vtk_read
    bad = [line for line in err.splitlines() if "ERR" in line or "Error" in line]
    assert not bad, "\n".join(bad[:5])
    assert np.allclose(data["times"], [0.0, 0.005, 0.01, 0.015, 0.02], rtol=0, atol=1e-12)
    assert set(data["blocks"]) == {"bodies", "surfaces", "elements"}
    assert len(data["blocks"]["bodies"]["points"]) == 9
    assert len(data["blocks"]["elements"]["cells"]) > 60


def test_surfaces_are_closed_triangle_meshes_of_every_body(vtk_read):
    s = vtk_read[0]["blocks"]["surfaces"]
    assert s["types"] == [5]                                   # VTK_TRIANGLE
    assert sorted(set(s["body"])) == list(range(1, 10))
    # the head: a latitude-longitude ellipsoid of 24 x 12; each vertebra a box
    head = max(set(s["body"]), key=s["body"].count)
    assert s["body"].count(head) == 2 * 24 * 11
    assert all(s["body"].count(k) == 12 for k in set(s["body"]) - {head})
    # closed: every edge is shared by exactly two triangles
    edges = {}
    for c in s["cells"]:
        for a, b in ((c[0], c[1]), (c[1], c[2]), (c[2], c[0])):
            edges[tuple(sorted((a, b)))] = edges.get(tuple(sorted((a, b))), 0) + 1
    assert set(edges.values()) == {2}
    assert len(s["points"]) == 2 + 11 * 24 + 8 * 8


def test_surface_vertices_against_the_bodies_mass_and_motion(vtk_read):
    data, _, h5 = vtk_read
    s = data["blocks"]["surfaces"]
    pts = np.array(s["points"])
    with h5py.File(h5, "r") as f:
        names = [str(n) for n in f["model"].attrs["bodies"]]
        time = f["time"][:]
        i = int(np.argmin(np.abs(time - data["times"][-1])))
        pos, rot = f["bodies/position"][i], f["bodies/rotation"][i]       # rot[k, j, i] = S_ij
        mass, inertia = f["model/mass"][:], f["model/inertia"][:]
    k = names.index("HEAD")
    vert = sorted({v for c, b in zip(s["cells"], s["body"]) if b == k + 1 for v in c})
    local = (pts[vert] - pos[k]) @ rot[k].T                  # rows S^T (p - r) (rot[k] read as S^T)
    w, axes = np.linalg.eigh(inertia[k])
    semi2 = 5.0 * (w.sum() - 2 * w) / (2 * mass[k])          # a_i^2 = 5 (I_j + I_k - I_i) / (2 m)
    q = np.sum((local @ axes) ** 2 / semi2, axis=1)
    assert np.all(semi2 > 0) and np.max(np.abs(q - 1.0)) < 1e-9
    # a vertebra's box: 8 corners, 12 edges in 3 groups of 4 equal lengths
    c4 = names.index("C4")
    corners = sorted({v for c, b in zip(s["cells"], s["body"]) if b == c4 + 1 for v in c})
    assert len(corners) == 8
    p = pts[corners]
    d = np.sort(np.linalg.norm(p[:, None] - p[None], axis=-1)[np.triu_indices(8, 1)])
    assert np.allclose(d[0:4], d[0], rtol=1e-9) and d[0] > 1e-3


def test_sidecar_surface_matches_what_vtk_read(vtk_read):
    data, _, h5 = vtk_read
    side = os.path.splitext(h5)[0] + ".elements.h5"
    with h5py.File(side, "r") as f:
        last = f["surface/points"].shape[0] - 1
        want = f["surface/points"][last]
        assert np.array_equal(f["step/%d/surface" % last][()], want)
    assert np.array_equal(np.array(data["blocks"]["surfaces"]["points"]), want)
