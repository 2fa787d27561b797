"""Write an XDMF file so ParaView opens a hhneck result file and animates it.

    hhneck-xdmf RESULT.h5 [--every 0.001]

writes RESULT.xmf next to RESULT.h5: a temporal collection with, at each
time step, the grid 'bodies' (the mass centres, joined child to parent as
polylines, with each body's x, y and z axes as point vectors for glyphs)
read straight from /bodies/position and /bodies/rotation of RESULT.h5, and
the grid 'elements' (ligaments, muscles, springs and discs as two-point
polylines with their force and family as cell data), and the grid
'surfaces': each body as a closed triangle mesh, the head as the uniform
ellipsoid with its mass and principal inertia (/model/mass, /model/inertia),
each vertebra as the box between its disc plates (the disc areas and
attachment points of /model/elements; animate.body_shapes), with the body
number as cell data. The elements' end points and the surfaces' vertices
are not in the result file: they are computed here from /model and the
body motion and stored in RESULT.elements.h5.
Open RESULT.xmf in ParaView (docs/animation.md). Needs numpy and h5py.
"""
import argparse
import os
import sys

import h5py
import numpy as np

from .animate import LINE_FAMILIES, Result, body_shapes

FAMILY_CODE = {"ligaments": 1, "muscles": 2, "springs": 3, "discs": 4}


def element_families(res):
    """(family key, family) of every family drawn, discs last."""
    fams = [(n, res.families[n]) for n in LINE_FAMILIES if n in res.families]
    if res.discs is not None:
        fams.append(("discs", res.discs))
    return fams


def element_segments(fams):
    """The straight segments drawn: (family code, family, element, (body,
    point) of each end) -- one per element, or one per leg of a muscle's
    path through its via points."""
    segs = []
    for key, fam in fams:
        for k in range(len(fam.name)):
            path = [(fam.body[k, 0], fam.point[k, 0])] + list(fam.via[k]) \
                + [(fam.body[k, 1], fam.point[k, 1])]
            segs += [(FAMILY_CODE[key], fam, k, path[j], path[j + 1]) for j in range(len(path) - 1)]
    return segs


def ellipsoid_mesh(axes, dirs, nlon=24, nlat=12):
    """Vertices (nv, 3) and triangles (nt, 3) of the ellipsoid with these
    semi-axes along the columns of dirs (a latitude-longitude mesh: two
    poles and nlat - 1 rings of nlon vertices), outward normals."""
    theta = np.pi * np.arange(1, nlat) / nlat                # polar angle of each ring
    phi = 2 * np.pi * np.arange(nlon) / nlon
    unit = [[0.0, 0.0, 1.0]] + [[np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)]
                                for t in theta for p in phi] + [[0.0, 0.0, -1.0]]
    verts = (np.array(unit) * axes) @ dirs.T
    ring = lambda r, k: 1 + r * nlon + k % nlon              # noqa: E731 (vertex k of ring r)
    tri = [(0, ring(0, k), ring(0, k + 1)) for k in range(nlon)]
    for r in range(nlat - 2):
        for k in range(nlon):
            tri += [(ring(r, k), ring(r + 1, k), ring(r + 1, k + 1)), (ring(r, k), ring(r + 1, k + 1), ring(r, k + 1))]
    last = len(unit) - 1
    tri += [(last, ring(nlat - 2, k + 1), ring(nlat - 2, k)) for k in range(nlon)]
    return verts, np.array(tri, dtype=np.int32)


def box_mesh(cx, r, lo, hi):
    """Vertices (8, 3) and triangles (12, 3) of the box [cx - r, cx + r] x
    [-r, r] x [lo, hi], outward normals."""
    verts = np.array([[cx + sx * r, sy * r, z] for z in (lo, hi) for sy in (-1, 1) for sx in (-1, 1)])
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tri = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return verts, np.array(tri, dtype=np.int32)


def body_surfaces(res):
    """Every body's surface in its own frame: vertices (nv, 3), the body of
    each vertex (1-based), triangles (nt, 3) into the vertices, the body of
    each triangle."""
    verts, vbody, tris, tbody = [], [], [], []
    for k, sh in enumerate(body_shapes(res), start=1):
        v, t = ellipsoid_mesh(sh[1], sh[2]) if sh[0] == "ellipsoid" else box_mesh(*sh[1:5])
        tris.append(t + sum(len(x) for x in verts))
        verts.append(v)
        vbody += [k] * len(v)
        tbody += [k] * len(t)
    return (np.vstack(verts), np.array(vbody, dtype=np.int32), np.vstack(tris).astype(np.int32),
            np.array(tbody, dtype=np.int32))


def write_sidecar(res, steps, path):
    """RESULT.elements.h5: end points (ns, 2 ne, 3), forces (ns, ne), connectivity,
    family codes and names of the segments drawn (an element, or one leg of
    a muscle's path through its via points) at the selected samples."""
    segs = element_segments(element_families(res))
    ne = len(segs)
    names = [fam.name[k] for _, fam, k, _, _ in segs]
    codes = np.array([c for c, _, _, _, _ in segs], dtype=np.int32)
    pts = np.empty((len(steps), 2 * ne, 3))
    force = np.empty((len(steps), ne))
    for e, (_, fam, k, a, b) in enumerate(segs):
        for end, (body, c) in enumerate((a, b)):
            pts[:, 2 * e + end] = c if body == 0 else res.pos[steps, body - 1] + res.rot[steps, body - 1] @ c
        force[:, e] = fam.force[steps, k]
    with h5py.File(path, "w") as f:
        f.attrs["source"] = "hhneck-xdmf"
        for name, data, units in (("time", res.time[steps], "s"), ("points", pts, "m"), ("force", force, "N"),
                                  ("connectivity", np.arange(2 * ne, dtype=np.int32).reshape(ne, 2), "none"),
                                  ("family", codes, "none")):
            f[name] = data
            f[name].attrs["units"] = units
        f["name"] = np.array([n.encode() for n in names], dtype="S12")
        f["name"].attrs["units"] = "none"
        f["family"].attrs["codes"] = "1 ligament, 2 muscle, 3 spring, 4 disc"
        verts, vbody, tris, tbody = body_surfaces(res)
        k = vbody - 1
        world = res.pos[steps][:, k] + np.einsum("skij,kj->ski", res.rot[steps][:, k], verts)
        g = f.create_group("surface")
        g.attrs["description"] = ("each body's surface: the head's uniform ellipsoid (its mass and principal "
                                  "inertia), the vertebrae's boxes between their disc plates")
        for name, data, units in (("points", world, "m"), ("triangles", tris, "none"), ("body", tbody, "none")):
            g[name] = data
            g[name].attrs["units"] = units
        # each step's geometry as a dataset of its own: VTK's XDMF reader
        # wants a geometry's DataItem to name its heavy dataset (a hyperslab
        # selection of a larger one gives an error line per grid)
        for s, i in enumerate(steps):
            for name, data in (("bodies", res.pos[i]), ("elements", pts[s]), ("surface", world[s])):
                f["step/%d/%s" % (s, name)] = data
        f["step"].attrs["description"] = ("step/S/bodies (nb, 3) mass centres, step/S/elements (2 ne, 3) element "
                                          "end points, step/S/surface (nv, 3) surface vertices at the S-th step [m]")
        f["force"].attrs["description"] = ("tension of ligaments and muscles, axial force of discs "
                                           "(tension positive); NaN where the result file has no channel")
    return ne


def hdf_item(fname, path, shape, number="Float", precision=8):
    return ('<DataItem Dimensions="%s" NumberType="%s" Precision="%d" Format="HDF">%s:%s</DataItem>'
            % (" ".join(map(str, shape)), number, precision, fname, path))


def hyperslab(fname, path, shape, start, count):
    """A DataItem selecting count (per dimension) from start of an HDF5 dataset."""
    sel = " ".join(map(str, start)) + "  " + " ".join(["1"] * len(shape)) + "  " + " ".join(map(str, count))
    dims = [c for c in count if c != 1] or [1]       # the selection without its unit dimensions
    return ('<DataItem ItemType="HyperSlab" Type="HyperSlab" Dimensions="%s">'
            '<DataItem Dimensions="3 %d" Format="XML">%s</DataItem>%s</DataItem>'
            % (" ".join(map(str, dims)), len(shape), sel, hdf_item(fname, path, shape)))


def xml_item(values, number="Int"):
    return '<DataItem Dimensions="%d" NumberType="%s" Format="XML">%s</DataItem>' % (
        len(values), number, " ".join(map(str, values)))


def write_xmf(res, steps, h5name, side_name, ne, path, surf):
    """The XDMF file: one spatial collection (bodies, elements) per selected sample."""
    nt, nb = len(res.time), res.nb
    rshape = (nt, nb, 3, 3)
    edges = [(res.parent[k] - 1, k) for k in range(nb) if res.parent[k] > 0]
    conn = xml_item([v for e in edges for v in e])
    conn = conn.replace('Dimensions="%d"' % (2 * len(edges)), 'Dimensions="%d 2"' % len(edges))
    bodies_no = xml_item(list(range(1, nb + 1)))
    ns = len(steps)
    out = ['<?xml version="1.0" ?>', '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>', '<Xdmf Version="2.0">',
           '<Domain>', '<Grid Name="hhneck" GridType="Collection" CollectionType="Temporal">']
    for s, i in enumerate(steps):
        out.append('<Grid Name="t%d" GridType="Collection" CollectionType="Spatial">' % s)
        out.append('<Time Value="%.9g"/>' % res.time[i])
        out.append('<Grid Name="bodies" GridType="Uniform">')
        out.append('<Topology TopologyType="Polyline" NumberOfElements="%d" NodesPerElement="2">%s</Topology>'
                   % (len(edges), conn))
        out.append('<Geometry GeometryType="XYZ">%s</Geometry>' % hdf_item(side_name, "/step/%d/bodies" % s, (nb, 3)))
        for j, axis in enumerate("xyz"):
            out.append('<Attribute Name="%s_axis" AttributeType="Vector" Center="Node">%s</Attribute>'
                       % (axis, hyperslab(h5name, "/bodies/rotation", rshape, (i, 0, j, 0), (1, nb, 1, 3))))
        out.append('<Attribute Name="body" AttributeType="Scalar" Center="Node">%s</Attribute>' % bodies_no)
        out.append('</Grid>')
        nv, nt = surf
        out.append('<Grid Name="surfaces" GridType="Uniform">')
        out.append('<Topology TopologyType="Triangle" NumberOfElements="%d">%s</Topology>'
                   % (nt, hdf_item(side_name, "/surface/triangles", (nt, 3), "Int", 4)))
        out.append('<Geometry GeometryType="XYZ">%s</Geometry>'
                   % hdf_item(side_name, "/step/%d/surface" % s, (nv, 3)))
        out.append('<Attribute Name="body" AttributeType="Scalar" Center="Cell">%s</Attribute>'
                   % hdf_item(side_name, "/surface/body", (nt,), "Int", 4))
        out.append('</Grid>')
        if ne > 0:
            out.append('<Grid Name="elements" GridType="Uniform">')
            out.append('<Topology TopologyType="Polyline" NumberOfElements="%d" NodesPerElement="2">%s</Topology>'
                       % (ne, hdf_item(side_name, "/connectivity", (ne, 2), "Int", 4)))
            out.append('<Geometry GeometryType="XYZ">%s</Geometry>'
                       % hdf_item(side_name, "/step/%d/elements" % s, (2 * ne, 3)))
            out.append('<Attribute Name="force" AttributeType="Scalar" Center="Cell">%s</Attribute>'
                       % hyperslab(side_name, "/force", (ns, ne), (s, 0), (1, ne)))
            out.append('<Attribute Name="family" AttributeType="Scalar" Center="Cell">%s</Attribute>'
                       % hdf_item(side_name, "/family", (ne,), "Int", 4))
            out.append('</Grid>')
        out.append('</Grid>')
    out += ['</Grid>', '</Domain>', '</Xdmf>', '']
    with open(path, "w") as f:
        f.write("\n".join(out))


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-xdmf", description=__doc__.split("\n\n")[0])
    p.add_argument("result", help="hhneck HDF5 result file")
    p.add_argument("--every", type=float, default=0.001,
                   help="time between XDMF steps [s] (default 0.001; 0: every sample)")
    args = p.parse_args(argv)
    res = Result(args.result)
    if args.every > 0:
        t = np.arange(res.time[0], res.time[-1] + 1e-12, args.every)
        steps = np.unique(np.clip(np.searchsorted(res.time, t - 1e-12), 0, len(res.time) - 1))
    else:
        steps = np.arange(len(res.time))
    stem = os.path.splitext(args.result)[0]
    xmf, side = stem + ".xmf", stem + ".elements.h5"
    ne = write_sidecar(res, steps, side)
    with h5py.File(side, "r") as f:
        surf = (f["surface/points"].shape[1], f["surface/triangles"].shape[0])
    write_xmf(res, steps, os.path.basename(args.result), os.path.basename(side), ne, xmf, surf)
    print("hhneck-xdmf: wrote %s (%d time steps, %d bodies, %d surface triangles, %d elements) and %s"
          % (xmf, len(steps), res.nb, surf[1], ne, side))
    return 0


if __name__ == "__main__":
    sys.exit(main())
