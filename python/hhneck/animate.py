#!/usr/bin/env python3
"""Animate a hhneck result file: the nine bodies, discs, ligaments and muscles.

    tools/animate.py RESULT.h5 OUT.gif            # GIF (matplotlib only)
    tools/animate.py RESULT.h5 OUT.mp4            # MP4 (needs ffmpeg)
    tools/animate.py RESULT.h5 --strip OUT.png    # key frames every 20 ms

Each frame shows a side (sagittal) view, a front view and a 3-D view that
follow T1's translation, with ground marks fixed in R so the sled's motion
shows, and the head angle against time. Vertebral bodies are boxes between
their disc plates, the head is the uniform ellipsoid with its mass and
principal inertia, discs, ligaments and muscles (through their via points)
are lines coloured by their force. Bodies come from /bodies/position and /bodies/rotation, elements from
/model/elements and their forces from /channels (docs/animation.md).
Needs numpy, h5py and matplotlib; MP4 also needs ffmpeg.
"""
import argparse
import shutil
import sys

import h5py
import numpy as np

TENSION_CMAP = "YlOrRd"     # ligaments and muscles: tension from 0 to the run's peak
DISC_CMAP = "coolwarm"      # discs: axial force, compression blue, tension red
SLACK_COLOUR = "0.75"       # a line element carrying no force
GROUND_STEP = 0.05          # spacing of the ground marks fixed in R [m]
SLED_X = (-0.12, 0.08)      # sled extent along x relative to T1's mass centre [m]
LINE_FAMILIES = ("ligaments", "muscles", "springs")


def text(v):
    """h5py string (bytes or str, possibly blank-padded) as str."""
    if isinstance(v, bytes):
        v = v.decode()
    return str(v).strip()


def text_list(v):
    """A list attribute as a list of str: an array of strings (schema 2) or
    one space-separated text (files before schema 2)."""
    if isinstance(v, (str, bytes)):
        return text(v).split()
    return [text(x) for x in v]


class Family:
    """One element family: names, bodies (0 = R), attachment points in body
    frames, and the force history (nt, ne) where the file has a channel."""

    def __init__(self, g, chan, suffix=""):
        self.name = [text(n) for n in g["name"][:]]
        self.body = np.asarray(g["body"][:], dtype=int).reshape(-1, 2)
        self.point = np.asarray(g["point"][:], dtype=float).reshape(-1, 2, 3)
        # a muscle's path through its via points (VIA cards): (body, point)
        # pairs between the two ends; none in older files or other families
        self.via = [[] for _ in self.name]
        if "via_count" in g:
            count = np.asarray(g["via_count"][:], dtype=int)
            vbody = np.asarray(g["via_body"][:], dtype=int).reshape(len(self.name), -1)
            vpoint = np.asarray(g["via_point"][:], dtype=float).reshape(len(self.name), -1, 3)
            self.via = [list(zip(vbody[e, :count[e]], vpoint[e, :count[e]])) for e in range(len(self.name))]
        nt = chan["_nt"]
        self.force = np.full((nt, len(self.name)), np.nan)
        for e, n in enumerate(self.name):
            if n + suffix in chan:
                self.force[:, e] = chan[n + suffix][:]


class Result:
    """The parts of a result file the drawing needs."""

    def __init__(self, path):
        with h5py.File(path, "r") as f:
            self.title = text(f.attrs.get("title", ""))
            self.status = text(f.attrs.get("status", ""))
            self.time = f["time"][:]
            self.pos = f["bodies/position"][:]
            # h5py index [t, k, j, i] is S_ij: swap to a matrix S[t, k][i, j]
            self.rot = np.swapaxes(f["bodies/rotation"][:], -1, -2)
            m = f["model"]
            self.bodies = text_list(m.attrs["bodies"])
            self.parent = m["parent"][:].astype(int)
            self.mass = m["mass"][:]
            self.inertia = np.swapaxes(m["inertia"][:], -1, -2)
            self.joint_in_body = m["joint_in_body"][:]
            self.joint_in_parent = m["joint_in_parent"][:]
            chan = {"_nt": len(self.time)}
            chan.update({k: f["channels"][k] for k in f["channels"]})
            self.families = {}
            self.discs = None
            if "elements" in m:
                for fam in LINE_FAMILIES:
                    if fam in m["elements"]:
                        self.families[fam] = Family(m["elements"][fam], chan)
                if "discs" in m["elements"]:
                    g = m["elements"]["discs"]
                    self.discs = Family(g, chan, "_P")
                    self.disc_area = g["area"][:]
            else:
                print("animate.py: %s has no /model/elements (written by an older hhneck): "
                      "drawing the bodies only" % path, file=sys.stderr)
        self.nb = len(self.bodies)
        self.root = int(np.flatnonzero(self.parent == 0)[0])
        self.head = self.bodies.index("HEAD") if "HEAD" in self.bodies else self.nb - 1

    def world(self, i, body, c):
        """Points c (..., 3) fixed in `body` (1-based, 0 = R) at sample i, in R."""
        if body == 0:
            return np.asarray(c, dtype=float)
        return self.pos[i, body - 1] + np.asarray(c) @ self.rot[i, body - 1].T

    def sagittal_angle(self, i, k, relative_to=None):
        """atan2(S13, S33) of body k (0-based) [deg], flexion positive; relative
        to body `relative_to` when given."""
        s = self.rot[i, k]
        if relative_to is not None:
            s = self.rot[i, relative_to].T @ s
        return np.degrees(np.arctan2(s[0, 2], s[2, 2]))

    def rotation_angle(self, i, k):
        """Angle of the rotation of body k from its neutral (R-parallel) axes [deg]."""
        c = (np.trace(self.rot[i, k]) - 1.0) / 2.0
        return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))

    def line_ends(self, i, fam):
        """(ne, 2, 3) end points in R of the elements of a family at sample i."""
        out = np.empty(fam.point.shape)
        for e in range(len(fam.name)):
            for end in range(2):
                out[e, end] = self.world(i, fam.body[e, end], fam.point[e, end])
        return out

    def line_paths(self, i, fam):
        """The path in R of each element of a family at sample i: (M, 3)
        points from end a through its via points (muscles) to end b."""
        ends = self.line_ends(i, fam)
        paths = []
        for e in range(len(fam.name)):
            via = [self.world(i, b, c) for b, c in fam.via[e]]
            paths.append(np.vstack([ends[e, 0]] + via + [ends[e, 1]]))
        return paths


def ellipsoid_axes(mass, inertia):
    """Semi-axes and principal directions of the uniform ellipsoid with this
    mass and centroidal inertia (I_1 = m (b^2 + c^2) / 5, ...)."""
    w, v = np.linalg.eigh(inertia)
    s = 5.0 * w / mass
    sq = 0.5 * (s.sum() - 2.0 * s)           # a_i^2 = (s_j + s_k - s_i) / 2
    if np.any(sq <= 0):
        return np.full(3, 0.09), np.eye(3)
    return np.sqrt(sq), v


def body_shapes(res):
    """Local outline of each body: ('box', centre_x, half_width, z_lo, z_hi,
    process_tip) for vertebrae (the tip a local point or None) and
    ('ellipsoid', semi_axes, principal_directions, None) for the head."""
    plates = {k: {"lo": None, "hi": None, "r": []} for k in range(1, res.nb + 1)}
    if res.discs is not None:
        for e in range(len(res.discs.name)):
            a, b = res.discs.body[e]
            r = np.sqrt(res.disc_area[e] / np.pi)
            if a > 0:
                plates[a]["hi"] = res.discs.point[e, 0]
                plates[a]["r"].append(r)
            if b > 0:
                plates[b]["lo"] = res.discs.point[e, 1]
                plates[b]["r"].append(r)
    shapes = []
    for k in range(1, res.nb + 1):
        if k - 1 == res.head:
            axes, dirs = ellipsoid_axes(res.mass[k - 1], res.inertia[k - 1])
            shapes.append(("ellipsoid", axes, dirs, None))
            continue
        p = plates[k]
        children = np.flatnonzero(res.parent == k)
        hi = p["hi"] if p["hi"] is not None else (
            res.joint_in_parent[children[0]] if len(children) else np.array([0, 0, 0.008]))
        lo = p["lo"] if p["lo"] is not None else (
            res.joint_in_body[k - 1] if res.parent[k - 1] > 0 else np.array([hi[0], 0, -hi[2]]))
        r = max(p["r"]) if p["r"] else 0.009
        cx = 0.5 * (lo[0] + hi[0])
        tip = None
        for fam in res.families.values():
            for e in range(len(fam.name)):
                for end in range(2):
                    c = fam.point[e, end]
                    if fam.body[e, end] == k and abs(c[1]) <= r and c[0] < cx - r:
                        if tip is None or c[0] < tip[0]:
                            tip = c
        shapes.append(("box", cx, r, lo[2], hi[2], tip))
    return shapes


def box_edges(cx, r, lo, hi):
    """Local (x, y, z) polylines of a box, NaN-separated: the 12 edges."""
    xs, ys, zs = (cx - r, cx + r), (-r, r), (lo, hi)
    segs = []
    for y in ys:
        for z in zs:
            segs.append([[xs[0], y, z], [xs[1], y, z]])
    for x in xs:
        for z in zs:
            segs.append([[x, ys[0], z], [x, ys[1], z]])
        for y in ys:
            segs.append([[x, y, zs[0]], [x, y, zs[1]]])
    return segs


def ellipse(axes, dirs, i, j, n=48):
    """Local points of the ellipsoid's section by the plane of body axes i, j."""
    a = dirs @ np.diag(1.0 / axes ** 2) @ dirs.T       # p^T a p = 1 on the surface
    u = np.linspace(0, 2 * np.pi, n)
    d = np.zeros((n, 3))
    d[:, i], d[:, j] = np.cos(u), np.sin(u)
    return d / np.sqrt(np.einsum("ni,ij,nj->n", d, a, d))[:, None]


def join(segs):
    """Segments (list of (m, 3)) joined into one NaN-separated (M, 3) array."""
    out = []
    for s in segs:
        out.extend(np.asarray(s, dtype=float))
        out.append([np.nan] * 3)
    return np.array(out[:-1]) if out else np.zeros((0, 3))


class Geometry:
    """The bodies' outlines and the sled and ground marks, in R, at one sample."""

    def __init__(self, res):
        self.res = res
        self.shapes = body_shapes(res)

    def bodies(self, i):
        """{'side': (M, 3), 'front': (M, 3), '3d': (M, 3)} outline points of each body."""
        out = []
        for k, sh in enumerate(self.shapes, start=1):
            if sh[0] == "ellipsoid":
                _, axes, dirs, _ = sh
                xz, yz, xy = ellipse(axes, dirs, 0, 2), ellipse(axes, dirs, 1, 2), ellipse(axes, dirs, 0, 1)
                a = np.sqrt(np.sum((axes * dirs[0]) ** 2))   # extent along the local x axis
                nose = [[a, 0, 0], [a + 0.025, 0, 0]]
                side, front, d3 = [xz, nose], [yz, nose], [xz, yz, xy, nose]
            else:
                _, cx, r, lo, hi, tip = sh
                rect_xz = [[cx - r, 0, lo], [cx + r, 0, lo], [cx + r, 0, hi], [cx - r, 0, hi], [cx - r, 0, lo]]
                rect_yz = [[cx, -r, lo], [cx, r, lo], [cx, r, hi], [cx, -r, hi], [cx, -r, lo]]
                proc = [[[cx - r, 0, 0.5 * (lo + hi)], tip]] if tip is not None else []
                side, front, d3 = [rect_xz] + proc, [rect_yz], box_edges(cx, r, lo, hi) + proc
            out.append({v: self.res.world(i, k, join(s)) for v, s in
                        (("side", side), ("front", front), ("3d", d3))})
        return out

    def sled(self, i, zfloor, xrange):
        """Sled under T1 (moves with T1) and ground marks fixed in R, in R."""
        x0 = self.res.pos[i, self.res.root, 0]
        y0 = self.res.pos[i, self.res.root, 1]
        sled = np.array([[x0 + xrange[0], y0 - 0.1, zfloor], [x0 + xrange[1], y0 - 0.1, zfloor],
                         [x0 + xrange[1], y0 + 0.1, zfloor], [x0 + xrange[0], y0 + 0.1, zfloor],
                         [x0 + xrange[0], y0 - 0.1, zfloor]])
        lo, hi = x0 + xrange[0] - 0.05, x0 + xrange[1] + 0.05
        marks = np.arange(np.ceil(lo / GROUND_STEP), np.floor(hi / GROUND_STEP) + 1) * GROUND_STEP
        zg = zfloor - 0.02
        ground = join([[[x, y0 - 0.1, zg], [x - 0.012, y0 - 0.1, zg - 0.012]] for x in marks]
                      + [[[lo, y0 - 0.1, zg], [hi, y0 - 0.1, zg]]])
        xs = self.res.pos[0, self.res.root, 0]              # where T1 started, fixed in R
        start = np.array([[xs, y0 - 0.1, zg], [xs, y0 - 0.1, zfloor + 0.04]])
        return sled, ground, start


def frame_indices(time, t_frames):
    """Index of the sample nearest to each frame time."""
    if len(time) < 2:
        return np.zeros(len(t_frames), dtype=int)
    j = np.clip(np.searchsorted(time, t_frames), 1, len(time) - 1)
    return np.where(np.abs(time[j - 1] - t_frames) <= np.abs(time[j] - t_frames), j - 1, j)


def view_window(res, geo, first, last):
    """Fixed extents of the views relative to T1's mass centre, from every
    drawn point of 60 samples between samples first and last: 'lo', 'hi'
    (plane views), 'lo3', 'hi3' (3-D view, a cube), 'zfloor' (the sled)."""
    pts = []
    for i in np.unique(np.linspace(first, last, 60).astype(int)):
        ref = res.pos[i, res.root]
        for b in geo.bodies(i):
            pts.append(b["3d"] - ref)
        for fam in res.families.values():
            pts.append(res.line_ends(i, fam).reshape(-1, 3) - ref)
    pts = np.vstack(pts)
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    lo, hi = pts.min(axis=0) - 0.02, pts.max(axis=0) + 0.02
    w = {"zfloor": lo[2] - 0.01}
    lo[2] -= 0.05
    span = (hi - lo).max()
    mid = 0.5 * (lo + hi)
    w.update(lo=lo, hi=hi, lo3=mid - 0.5 * span, hi3=mid + 0.5 * span)
    return w


class Scene:
    """The artists of the views; update(i) sets them to sample i."""

    PLANES = {"side": (0, 2), "front": (1, 2)}

    def __init__(self, res, frames, axes, fmax=None, history_ax=None, label_text=None):
        import matplotlib.pyplot as plt
        from matplotlib import colors
        self.res, self.geo, self.axes = res, Geometry(res), axes
        self.tension_cmap = plt.get_cmap(TENSION_CMAP)
        self.disc_cmap = plt.get_cmap(DISC_CMAP)
        span = slice(frames[0], frames[-1] + 1)           # colour scales: every sample drawn over
        peak = [np.nanmax(f.force[span]) for f in res.families.values()
                if len(f.name) and np.any(np.isfinite(f.force[span]))]
        self.fmax = fmax or max(peak + [1.0])
        pmax = 1.0
        if res.discs is not None and len(res.discs.name) and np.any(np.isfinite(res.discs.force[span])):
            pmax = max(1.0, np.nanmax(np.abs(res.discs.force[span])))
        self.tension_norm = colors.Normalize(0.0, self.fmax)
        self.disc_norm = colors.Normalize(-pmax, pmax)
        self.win = view_window(res, self.geo, frames[0], frames[-1])
        self.artists = {v: self.make_artists(v, ax) for v, ax in axes.items()}
        self.history_ax, self.label_text = history_ax, label_text
        if history_ax is not None:
            self.cursor = history_ax.axvline(0.0, color="k", lw=0.8)

    def make_artists(self, view, ax):
        a = {"bodies": [], "cm": {}, "lines": {}, "discs": {}}
        is3d = view == "3d"

        def line(**kw):
            return ax.plot(*([[], [], []] if is3d else [[], []]), **kw)[0]
        a["ground"] = line(color="0.45", lw=0.8)
        a["sled"] = line(color="0.3", lw=2.0)
        a["start"] = line(color="0.45", lw=0.8, ls=":")
        for k, name in enumerate(self.res.bodies):
            a["bodies"].append(line(color="k", lw=1.0, zorder=4))
            a["cm"][name] = line(marker="o", ms=2.5, color="k", ls="none", zorder=5)
        for fam_name, fam in self.res.families.items():
            lw = {"muscles": 1.8, "ligaments": 0.9}.get(fam_name, 1.2)
            ls = "--" if fam_name == "springs" else "-"
            for n in fam.name:
                a["lines"][n] = line(lw=lw, ls=ls, color=SLACK_COLOUR)
        if self.res.discs is not None:
            for n in self.res.discs.name:
                a["discs"][n] = line(lw=3.5, color="0.5", solid_capstyle="butt", zorder=3)
        if is3d:
            ax.set_xlabel("x [m]", fontsize=7, labelpad=-8)
            ax.set_ylabel("y [m]", fontsize=7, labelpad=-8)
            ax.set_zlabel("z [m]", fontsize=7, labelpad=-8)
            for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
                axis.set_ticklabels([])
            ax.set_box_aspect((1, 1, 1), zoom=1.25)
            ax.view_init(elev=15, azim=-55)
        else:
            h, v = self.PLANES[view]
            ax.set_aspect("equal")
            ax.tick_params(labelsize=7)
            ax.set_xlabel("xyz"[h] + " [m]", fontsize=7)
            ax.set_ylabel("z [m]", fontsize=7)
        return a

    def put(self, art, view, p):
        """Set a line artist to R points p (M, 3), projected for the view."""
        if view == "3d":
            art.set_data_3d(p[:, 0], p[:, 1], p[:, 2])
        else:
            h, v = self.PLANES[view]
            art.set_data(p[:, h], p[:, v])

    def force_colour(self, f, disc=False):
        if not np.isfinite(f):
            return SLACK_COLOUR
        if disc:
            return self.disc_cmap(self.disc_norm(f))
        return SLACK_COLOUR if f <= 0.0 else self.tension_cmap(0.15 + 0.85 * self.tension_norm(f))

    def update(self, i):
        res, geo = self.res, self.geo
        ref = res.pos[i, res.root]
        bodies = geo.bodies(i)
        sled, ground, start = geo.sled(i, ref[2] + self.win["zfloor"], SLED_X)
        ends = {n: e for fam in res.families.values() for n, e in zip(fam.name, res.line_paths(i, fam))}
        forces = {n: f for fam in res.families.values() for n, f in zip(fam.name, fam.force[i])}
        dends = {}
        if res.discs is not None:
            dends = dict(zip(res.discs.name, res.line_ends(i, res.discs)))
        for view, a in self.artists.items():
            for k, name in enumerate(res.bodies):
                self.put(a["bodies"][k], view, bodies[k][view])
                self.put(a["cm"][name], view, res.pos[i, k][None, :])
            for n, art in a["lines"].items():
                self.put(art, view, ends[n])
                art.set_color(self.force_colour(forces[n]))
            for e, (n, art) in enumerate(a["discs"].items()):
                self.put(art, view, dends[n])
                art.set_color(self.force_colour(res.discs.force[i, e], disc=True))
            self.put(a["sled"], view, sled)
            self.put(a["ground"], view, ground)
            self.put(a["start"], view, start)
            ax = self.axes[view]
            if view == "3d":
                lo, hi = ref + self.win["lo3"], ref + self.win["hi3"]
                ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
            else:
                h, v = self.PLANES[view]
                lo, hi = ref + self.win["lo"], ref + self.win["hi"]
                ax.set_xlim(lo[h], hi[h]); ax.set_ylim(lo[v], hi[v])
        if self.history_ax is not None:
            self.cursor.set_xdata([1000 * res.time[i]] * 2)
        if self.label_text is not None:
            self.label_text.set_text(frame_label(res, i))


def frame_label(res, i):
    """Time, head rotation and T1 displacement at sample i."""
    h, r = res.head, res.root
    dx = 1000 * (res.pos[i, r, 0] - res.pos[0, r, 0])
    return ("t = %6.1f ms    head flexion %.1f deg (%.1f deg relative to %s), rotation %.1f deg"
            "    %s x displacement %.1f mm"
            % (1000 * res.time[i], res.sagittal_angle(i, h), res.sagittal_angle(i, h, r),
               res.bodies[r], res.rotation_angle(i, h), res.bodies[r], dx))


def add_colourbars(fig, scene, axes):
    from matplotlib import cm
    for norm, cmap, label in ((scene.tension_norm, scene.tension_cmap, "ligament / muscle tension [N]"),
                              (scene.disc_norm, scene.disc_cmap, "disc axial force [N] (compression < 0)")):
        sm = cm.ScalarMappable(norm=norm, cmap=cmap)
        cb = fig.colorbar(sm, cax=axes.pop(0), orientation="horizontal")
        cb.set_label(label, fontsize=7)
        cb.ax.tick_params(labelsize=7)


def build_figure(res, frames, dpi, fmax=None, rate_label=""):
    """The animation figure: side, front and 3-D views, head angle against
    time, colour bars; returns (fig, scene)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    w = 2 * round(12.0 * dpi / 2) / dpi                 # even pixel sizes (H.264)
    h = 2 * round(7.0 * dpi / 2) / dpi
    fig = plt.figure(figsize=(w, h), dpi=dpi)
    win = view_window(res, Geometry(res), frames[0], frames[-1])
    ext = win["hi"] - win["lo"]
    gs = fig.add_gridspec(2, 3, height_ratios=[3.3, 1], width_ratios=[ext[0], max(ext[1], 0.5 * ext[0]), ext[2]],
                          left=0.05, right=0.98, top=0.88, bottom=0.08, wspace=0.25, hspace=0.3)
    axes = {"side": fig.add_subplot(gs[0, 0]), "front": fig.add_subplot(gs[0, 1]),
            "3d": fig.add_subplot(gs[0, 2], projection="3d")}
    axes["side"].set_title("side (sagittal) view, face to the right", fontsize=8)
    axes["front"].set_title("front view, subject's left to the right", fontsize=8)
    axes["3d"].set_title("3-D view", fontsize=8)
    hist = fig.add_subplot(gs[1, 0:2])
    t = 1000 * res.time
    hist.plot(t, [res.sagittal_angle(i, res.head) for i in range(len(t))], lw=1.2, label="head")
    hist.plot(t, [res.sagittal_angle(i, res.root) for i in range(len(t))], lw=1.0,
              label=res.bodies[res.root])
    hist.set_xlim(t[frames[0]], t[frames[-1]])
    hist.set_xlabel("time [ms]", fontsize=7)
    hist.set_ylabel("flexion [deg]", fontsize=7)
    hist.tick_params(labelsize=7)
    hist.legend(fontsize=7, loc="best")
    hist.grid(alpha=0.3)
    cbg = gs[1, 2].subgridspec(2, 1, hspace=2.5)
    cax = [fig.add_subplot(cbg[0]), fig.add_subplot(cbg[1])]
    head = res.title + ("" if res.status in ("complete", "") else "  [run %s]" % res.status)
    fig.text(0.5, 0.975, head, ha="center", va="top", fontsize=9, weight="bold")
    label = fig.text(0.5, 0.945, "", ha="center", va="top", fontsize=8, family="monospace")
    fig.text(0.98, 0.012, rate_label, ha="right", fontsize=7)
    scene = Scene(res, frames, axes, fmax=fmax, history_ax=hist, label_text=label)
    add_colourbars(fig, scene, cax)
    return fig, scene


def animation_frames(res, start, end, fps, slow):
    """Sample indices of the frames: one every 1/(fps slow) s of model time."""
    t0 = res.time[0] if start is None else max(start, res.time[0])
    t1 = res.time[-1] if end is None else min(end, res.time[-1])
    dt = 1.0 / (fps * slow)
    n = int(np.floor((t1 - t0) / dt + 1e-9)) + 1
    return frame_indices(res.time, t0 + dt * np.arange(n))


def write_animation(res, out, args):
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib import animation
    frames = animation_frames(res, args.start, args.end, args.fps, args.slow)
    rate = "real time" if args.slow == 1 else "slow motion %gx" % args.slow
    fig, scene = build_figure(res, frames, args.dpi, args.fmax,
                              "%s, %g frames/s, %d frames" % (rate, args.fps, len(frames)))
    if out.lower().endswith(".gif"):
        writer = animation.PillowWriter(fps=args.fps)
    else:
        writer = animation.FFMpegWriter(fps=args.fps, codec="libx264",
                                        extra_args=["-pix_fmt", "yuv420p"])
    with writer.saving(fig, out, dpi=args.dpi):
        for n, i in enumerate(frames):
            scene.update(i)
            writer.grab_frame()
            if not args.quiet and (n % 25 == 0 or n == len(frames) - 1):
                print("animate.py: frame %d of %d (t = %.1f ms)" % (n + 1, len(frames), 1000 * res.time[i]),
                      file=sys.stderr)
    return len(frames)


def write_strip(res, out, every, dpi, fmax=None, start=None, end=None):
    """Key-frame strip: side views every `every` seconds, in rows of up to 7."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t0 = res.time[0] if start is None else start
    t1 = res.time[-1] if end is None else min(end, res.time[-1])
    frames = frame_indices(res.time, np.arange(t0, t1 + 1e-9, every))
    ncol = min(len(frames), 7)
    nrow = -(-len(frames) // ncol)
    fig, axs = plt.subplots(nrow, ncol, figsize=(2.2 * ncol + 1.0, 2.7 * nrow + 0.6), dpi=dpi,
                            squeeze=False, gridspec_kw={"wspace": 0.05, "hspace": 0.3})
    fig.subplots_adjust(left=0.01, right=0.88, top=1 - 0.75 / (2.7 * nrow + 0.6), bottom=0.02)
    moves = np.ptp(res.pos[:, res.root, 0]) > 1e-3
    scene = None
    for n, i in enumerate(frames):
        ax = axs.flat[n]
        scene = Scene(res, frames, {"side": ax}, fmax=fmax)
        scene.update(i)
        ax.set_xticks([]); ax.set_yticks([]); ax.set_xlabel(""); ax.set_ylabel("")
        title = "%.0f ms  head %+.0f deg" % (1000 * res.time[i], res.sagittal_angle(i, res.head))
        if moves:
            dx = round(1000 * (res.pos[i, res.root, 0] - res.pos[0, res.root, 0])) + 0.0   # no "-0"
            title += "\n%s dx %+.0f mm" % (res.bodies[res.root], dx)
        ax.set_title(title, fontsize=8)
    for ax in axs.flat[len(frames):]:
        ax.axis("off")
    fig.suptitle(res.title + " (side views every %.0f ms, ground marks %.0f mm apart)"
                 % (1000 * every, 1000 * GROUND_STEP), fontsize=9)
    from matplotlib import cm
    for n, (norm, cmap, label) in enumerate(((scene.tension_norm, scene.tension_cmap, "tension [N]"),
                                             (scene.disc_norm, scene.disc_cmap, "disc axial [N]"))):
        cax = fig.add_axes([0.9 + 0.05 * n, 0.12, 0.012, 0.7])
        cb = fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax)
        cb.set_label(label, fontsize=7)
        cb.ax.tick_params(labelsize=6)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return len(frames)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("result", help="hhneck HDF5 result file")
    p.add_argument("out", nargs="?", help="animation to write: NAME.gif or NAME.mp4")
    p.add_argument("--slow", type=float, default=20.0,
                   help="slow-motion factor: 1 is real time, 20 (default) plays 1 ms of the run in 20 ms")
    p.add_argument("--fps", type=float, default=25.0, help="frames per second of the video (default 25)")
    p.add_argument("--start", type=float, help="first time drawn [s] (default: the file's first sample)")
    p.add_argument("--end", type=float, help="last time drawn [s] (default: the file's last sample)")
    p.add_argument("--dpi", type=float, default=80.0,
                   help="resolution: the frame is 12 x 7 inches, 960 x 560 pixels at the default 80")
    p.add_argument("--fmax", type=float,
                   help="tension at the top of the colour scale [N] (default: the peak between the first and last frame)")
    p.add_argument("--strip", metavar="PNG", help="also write a key-frame strip of side views")
    p.add_argument("--every", type=float, default=0.02, help="key-frame interval of the strip [s] (default 0.02)")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    args = p.parse_args(argv)
    if args.out is None and args.strip is None:
        p.error("give an output animation (OUT.gif or OUT.mp4) or --strip PNG")
    if args.out is not None:
        suffix = args.out.lower().rsplit(".", 1)[-1]
        if suffix not in ("gif", "mp4"):
            p.error("the animation must be NAME.gif or NAME.mp4, not %s" % args.out)
        if suffix == "mp4" and shutil.which("ffmpeg") is None:
            print("animate.py: MP4 needs ffmpeg, which is not installed: install it "
                  "(sudo apt-get install ffmpeg) or ask for OUT.gif instead", file=sys.stderr)
            return 2
    if args.slow <= 0 or args.fps <= 0 or args.every <= 0:
        p.error("--slow, --fps and --every must be positive")
    res = Result(args.result)
    if args.out is not None:
        n = write_animation(res, args.out, args)
        print("animate.py: wrote %s (%d frames)" % (args.out, n))
    if args.strip is not None:
        n = write_strip(res, args.strip, args.every, min(args.dpi, 100.0) + 20, args.fmax, args.start, args.end)
        print("animate.py: wrote %s (%d key frames)" % (args.strip, n))
    return 0


if __name__ == "__main__":
    sys.exit(main())
