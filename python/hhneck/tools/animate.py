"""Animate a hhneck result file: the nine bodies, discs, ligaments and muscles.

    hhneck-animate RESULT.h5 OUT.gif            # GIF (matplotlib only)
    hhneck-animate RESULT.h5 OUT.mp4            # MP4 (needs ffmpeg)
    hhneck-animate RESULT.h5 OUT                # OUT.mp4 with ffmpeg, else OUT.gif
    hhneck-animate RESULT.h5 --strip OUT.png    # key frames every 20 ms
    hhneck-animate RESULT.h5 --strip OUT.png --view front,side

Each frame shows the views that show the head's motion relative to T1 (or
those named by --view: side, front, top, iso), which follow T1's
translation, with ground marks fixed in R so the sled's motion shows, and
the head angle against time. Vertebral bodies are boxes between
their disc plates, the head is the uniform ellipsoid with its mass and
principal inertia, discs, ligaments and muscles (through their via points)
are lines coloured by their force. Bodies come from /bodies/position and /bodies/rotation, elements from
/model/elements and their forces from /channels (docs/animation.md).
The animation draws the figure once and then, at each frame, only the
moving artists over it (fixed view limits relative to T1), handing the
Agg buffer straight to the GIF quantizer (Pillow) or to ffmpeg.
Needs numpy, h5py and matplotlib (with Pillow); MP4 also needs ffmpeg.
"""
import argparse
import os
import shutil
import sys

import h5py
import numpy as np

from ..results import rotation_angle, text, text_list

TENSION_CMAP = "YlOrRd"     # ligaments and muscles: tension from 0 to the run's peak
DISC_CMAP = "coolwarm"      # discs: axial force, compression blue, tension red
SLACK_COLOUR = "0.75"       # a line element carrying no force
GROUND_STEP = 0.05          # spacing of the ground marks fixed in R [m]
SLED_X = (-0.12, 0.08)      # sled extent along x relative to T1's mass centre [m]
LINE_FAMILIES = ("ligaments", "muscles", "springs")
# the views: a plane view draws R's axes (horizontal, vertical) and looks
# along the third (its normal); "iso" is the 3-D view
PLANES = {"side": (0, 2, 1), "front": (1, 2, 0), "top": (0, 1, 2)}
VIEWS = ("side", "front", "top", "iso")
AUTO_SHARE = 0.5            # auto: the plane views with at least this share of the largest motion
TITLES = {"side": "side (sagittal) view, face to the right",
          "front": "front view, subject's left to the right",
          "top": "top view, face to the right, subject's left up",
          "iso": "3-D view"}
AXIS_NAMES = "xyz"


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
        # every element's path as one list of (body, point): its end a, via
        # points, end b; path_start[e] .. path_start[e + 1] are element e's
        path = [[(self.body[e, 0], self.point[e, 0])] + list(self.via[e]) + [(self.body[e, 1], self.point[e, 1])]
                for e in range(len(self.name))]
        self.path_body = np.array([b for p in path for b, _ in p], dtype=int)
        self.path_point = np.array([c for p in path for _, c in p], dtype=float).reshape(-1, 3)
        self.path_start = np.cumsum([0] + [len(p) for p in path])
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
                print("hhneck-animate: %s has no /model/elements (written by an older hhneck): "
                      "drawing the bodies only" % path, file=sys.stderr)
        self.nb = len(self.bodies)
        self.root = int(np.flatnonzero(self.parent == 0)[0])
        self.head = self.bodies.index("HEAD") if "HEAD" in self.bodies else self.nb - 1

    def world(self, i, body, c):
        """Points c (..., 3) fixed in `body` (1-based, 0 = R) at sample i, in R."""
        if body == 0:
            return np.asarray(c, dtype=float)
        return self.pos[i, body - 1] + np.asarray(c) @ self.rot[i, body - 1].T

    def world_many(self, i, bodies, c):
        """Points c (M, 3), point m fixed in body bodies[m] (1-based, 0 = R),
        at sample i, in R: r + S c for each (one vectorised step)."""
        b = np.asarray(bodies, dtype=int)
        k = np.maximum(b - 1, 0)
        out = self.pos[i, k] + np.einsum("mij,mj->mi", self.rot[i, k], c)
        return np.where((b == 0)[:, None], c, out)

    def sagittal_angle(self, i, k, relative_to=None):
        """atan2(S13, S33) of body k (0-based) [deg], flexion positive; relative
        to body `relative_to` when given."""
        s = self.rot[i, k]
        if relative_to is not None:
            s = self.rot[i, relative_to].T @ s
        return np.degrees(np.arctan2(s[0, 2], s[2, 2]))

    def view_angle(self, i, k, view, relative_to=None):
        """Rotation of body k (0-based) about the normal of a plane view
        [deg] (side: atan2(S13, S33), flexion positive, the channel
        HEAD_THETY; front: about x, atan2(S32, S33); top: about z,
        atan2(S21, S11)); the total rotation angle for the 3-D view."""
        s = self.rot[i, k]
        if relative_to is not None:
            s = self.rot[i, relative_to].T @ s
        if view == "side":
            return np.degrees(np.arctan2(s[0, 2], s[2, 2]))
        if view == "front":
            return np.degrees(np.arctan2(s[2, 1], s[2, 2]))
        if view == "top":
            return np.degrees(np.arctan2(s[1, 0], s[0, 0]))
        return float(rotation_angle(np.trace(s)))

    def rotation_angle(self, i, k):
        """Angle of the rotation of body k from its neutral (R-parallel) axes [deg]."""
        return float(rotation_angle(np.trace(self.rot[i, k])))

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
        pts = self.world_many(i, fam.path_body, fam.path_point)
        return [pts[a:b] for a, b in zip(fam.path_start[:-1], fam.path_start[1:])]


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
        self.local = self.local_outlines()

    def bodies(self, i):
        """{'side': (M, 3), 'front': (M, 3), 'top': (M, 3), 'iso': (M, 3)} outline points of each body."""
        return [{v: self.res.world(i, k, c) for v, c in local.items()}
                for k, local in enumerate(self.local, start=1)]

    def body_parts(self, i, view):
        """The bodies' outlines for a view at sample i, in R: a list of
        polylines (M, 3) without NaN (one vectorised transform)."""
        if not hasattr(self, "_parts"):
            self._parts = {}
            for v in VIEWS:
                pts = [(k, c) for k, local in enumerate(self.local, start=1) for c in local[v]]
                body = np.array([k for k, _ in pts], dtype=int)
                c = np.array([c for _, c in pts], dtype=float)
                gap = np.flatnonzero(np.isnan(c[:, 0]))
                keep = ~np.isnan(c[:, 0])
                # part boundaries: a NaN row, or a change of body
                cut = sorted(set(gap.tolist()) | set(np.flatnonzero(np.diff(body) != 0) + 1))
                self._parts[v] = (body[keep], c[keep], np.searchsorted(np.flatnonzero(keep), cut))
        body, c, cut = self._parts[view]
        w = self.res.world_many(i, body, c)
        return [p for p in np.split(w, cut) if len(p)]

    def local_outlines(self):
        """Each body's outline for each view in its own frame, NaN-separated
        polylines (fixed in the body: computed once)."""
        out = []
        for sh in self.shapes:
            if sh[0] == "ellipsoid":
                _, axes, dirs, _ = sh
                xz, yz, xy = ellipse(axes, dirs, 0, 2), ellipse(axes, dirs, 1, 2), ellipse(axes, dirs, 0, 1)
                a = np.sqrt(np.sum((axes * dirs[0]) ** 2))   # extent along the local x axis
                nose = [[a, 0, 0], [a + 0.025, 0, 0]]
                side, front, top, d3 = [xz, nose], [yz, nose], [xy, nose], [xz, yz, xy, nose]
            else:
                _, cx, r, lo, hi, tip = sh
                rect_xz = [[cx - r, 0, lo], [cx + r, 0, lo], [cx + r, 0, hi], [cx - r, 0, hi], [cx - r, 0, lo]]
                rect_yz = [[cx, -r, lo], [cx, r, lo], [cx, r, hi], [cx, -r, hi], [cx, -r, lo]]
                m = 0.5 * (lo + hi)
                rect_xy = [[cx - r, -r, m], [cx + r, -r, m], [cx + r, r, m], [cx - r, r, m], [cx - r, -r, m]]
                proc = [[[cx - r, 0, m], tip]] if tip is not None else []
                side, front, top = [rect_xz] + proc, [rect_yz], [rect_xy] + proc
                d3 = box_edges(cx, r, lo, hi) + proc
            out.append({v: join(s) for v, s in (("side", side), ("front", front), ("top", top), ("iso", d3))})
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
            pts.append(b["iso"] - ref)
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
    """The artists of the views; update(i) sets them to sample i.

    animated=False: every artist in R's coordinates, the views' limits moved
    with T1 at each update (the strip, and a figure drawn whole). animated=
    True (the animation's fast path): the views' limits are fixed and every
    drawn point is taken relative to T1's mass centre, so the axes, ticks,
    titles, colour bars and the history plot are drawn once and each frame
    redraws only the moving artists (self.moving) over that background."""

    def __init__(self, res, frames, axes, fmax=None, history_ax=None, label_text=None, animated=False):
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
        self.animated = animated
        self.artists = {v: self.make_artists(v, ax) for v, ax in axes.items()}
        self.history_ax, self.label_text = history_ax, label_text
        self.moving = []            # (axes or figure, artist) redrawn at each frame when animated
        if history_ax is not None:
            self.cursor = history_ax.axvline(0.0, color="k", lw=0.8)
            self.moving.append((history_ax, self.cursor))
        if label_text is not None and not animated:
            self.moving.append((label_text.figure, label_text))
        if label_text is not None and animated:
            self.label_values = self.split_label(label_text)
            self.moving += [(label_text.figure, t) for t in self.label_values]
        for v, a in self.artists.items():
            arts = [a["ground"], a["sled"], a["start"]] + list(a["lines"].values()) + [a["discs"], a["bodies"], a["cm"]]
            self.moving += [(axes[v], art) for art in arts if art is not None]     # in the order of their zorder
        if animated:
            for _, art in self.moving:
                art.set_animated(True)
            self.fix_limits()

    def make_artists(self, view, ax):
        """The view's artists: sled, ground and start marks, the body outlines
        (one line collection), the mass centres (one marker line), one line
        collection per element family (self.index: element name -> (family,
        position in its collection)) and one for the discs."""
        from matplotlib.collections import LineCollection
        from mpl_toolkits.mplot3d.art3d import Line3DCollection
        a = {"lines": {}}
        is3d = view == "iso"

        def line(**kw):
            return ax.plot(*([[], [], []] if is3d else [[], []]), **kw)[0]

        def collection(**kw):
            c = Line3DCollection([], **kw) if is3d else LineCollection([], **kw)
            ax.add_collection(c)
            return c
        a["ground"] = line(color="0.45", lw=0.8)
        a["sled"] = line(color="0.3", lw=2.0)
        a["start"] = line(color="0.45", lw=0.8, ls=":")
        a["bodies"] = collection(colors="k", linewidths=1.0, zorder=4)
        a["cm"] = line(marker="o", ms=2.5, color="k", ls="none", zorder=5)
        self.index = {}
        for family_name, fam in self.res.families.items():
            lw = {"muscles": 1.8, "ligaments": 0.9}.get(family_name, 1.2)
            ls = "--" if family_name == "springs" else "-"
            a["lines"][family_name] = collection(linewidths=lw, linestyles=ls, colors=SLACK_COLOUR)
            self.index.update((n, (family_name, k)) for k, n in enumerate(fam.name))
        a["discs"] = None
        if self.res.discs is not None:
            a["discs"] = collection(linewidths=3.5, colors="0.5", capstyle="butt", zorder=3)
            self.index.update((n, ("discs", k)) for k, n in enumerate(self.res.discs.name))
        if is3d:
            ax.set_xlabel("x [m]", fontsize=7, labelpad=-8)
            ax.set_ylabel("y [m]", fontsize=7, labelpad=-8)
            ax.set_zlabel("z [m]", fontsize=7, labelpad=-8)
            for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
                axis.set_ticklabels([])
            ax.set_box_aspect((1, 1, 1), zoom=1.25)
            ax.view_init(elev=15, azim=-55)
        else:
            h, v, _ = PLANES[view]
            ax.set_aspect("equal")
            ax.tick_params(labelsize=7)
            ax.set_xlabel(AXIS_NAMES[h] + " [m]", fontsize=7)
            ax.set_ylabel(AXIS_NAMES[v] + " [m]", fontsize=7)
        return a

    def split_label(self, label):
        """The animated frame label: its words drawn once (the template with
        blanks for the numbers, a monospace text), the numbers as their own
        texts over the blanks (fewer glyphs to draw at each frame)."""
        fig = label.figure
        template = frame_label_template(self.res)
        blanks = template.format(*(" " * w for w in LABEL_WIDTHS))
        label.set_text(blanks)
        box = label.get_window_extent(fig.canvas.get_renderer())
        cw = box.width / len(blanks)
        starts, k = [], 0
        for part, w in zip(template.split("{}")[:-1], LABEL_WIDTHS):
            k += len(part)
            starts.append(k)
            k += w
        x, y = label.get_position()
        return [fig.text((box.x0 + cw * c) / fig.bbox.width, y, "", ha="left", va="top", fontsize=label.get_fontsize(),
                         family="monospace") for c in starts]

    def fix_limits(self):
        """The animation's fixed view limits, relative to T1's mass centre."""
        for view, ax in self.axes.items():
            if view == "iso":
                lo, hi = self.win["lo3"], self.win["hi3"]
                ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
            else:
                h, v, _ = PLANES[view]
                lo, hi = self.win["lo"], self.win["hi"]
                ax.set_xlim(lo[h], hi[h]); ax.set_ylim(lo[v], hi[v])
                ax.set_xlabel("%s - %s's [m]" % (AXIS_NAMES[h], self.res.bodies[self.res.root]), fontsize=7)
                ax.set_ylabel("%s - %s's [m]" % (AXIS_NAMES[v], self.res.bodies[self.res.root]), fontsize=7)

    def put(self, art, view, p):
        """Set a line artist to R points p (M, 3), projected for the view."""
        if view == "iso":
            art.set_data_3d(p[:, 0], p[:, 1], p[:, 2])
        else:
            h, v, _ = PLANES[view]
            art.set_data(p[:, h], p[:, v])

    def put_segments(self, coll, view, paths):
        """Set a line collection to the R polylines `paths` (each (M, 3)),
        projected for the view."""
        if view == "iso":
            coll.set_segments(paths)
        else:
            h, v, _ = PLANES[view]
            coll.set_segments([p[:, [h, v]] for p in paths])

    def force_colours(self, f, disc=False):
        """RGBA colours (n, 4) of forces f: discs by axial force, ligaments and
        muscles by tension (slack grey at zero, or where there is no channel)."""
        from matplotlib.colors import to_rgba
        f = np.asarray(f, dtype=float)
        out = np.tile(to_rgba(SLACK_COLOUR), (len(f), 1))
        ok = np.isfinite(f) if disc else np.isfinite(f) & (f > 0.0)
        if ok.any():
            out[ok] = self.disc_cmap(self.disc_norm(f[ok])) if disc else \
                self.tension_cmap(0.15 + 0.85 * self.tension_norm(f[ok]))
        return out

    def update(self, i):
        res, geo = self.res, self.geo
        ref = res.pos[i, res.root]
        off = ref if self.animated else np.zeros(3)      # animated: every point relative to T1's
        sled, ground, start = geo.sled(i, ref[2] + self.win["zfloor"], SLED_X)
        paths = {k: [p - off for p in res.line_paths(i, fam)] for k, fam in res.families.items()}
        colour = {k: self.force_colours(fam.force[i]) for k, fam in res.families.items()}
        if res.discs is not None:
            paths["discs"] = list(res.line_ends(i, res.discs) - off)
            colour["discs"] = self.force_colours(res.discs.force[i], disc=True)
        for view, a in self.artists.items():
            self.put_segments(a["bodies"], view, [p - off for p in geo.body_parts(i, view)])
            self.put(a["cm"], view, res.pos[i] - off)
            for k, coll in list(a["lines"].items()) + ([("discs", a["discs"])] if a["discs"] is not None else []):
                self.put_segments(coll, view, paths[k])
                coll.set_color(colour[k])
            self.put(a["sled"], view, sled - off)
            self.put(a["ground"], view, ground - off)
            self.put(a["start"], view, start - off)
            if self.animated:
                continue
            ax = self.axes[view]
            if view == "iso":
                lo, hi = ref + self.win["lo3"], ref + self.win["hi3"]
                ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
            else:
                h, v, _ = PLANES[view]
                lo, hi = ref + self.win["lo"], ref + self.win["hi"]
                ax.set_xlim(lo[h], hi[h]); ax.set_ylim(lo[v], hi[v])
        if self.history_ax is not None:
            self.cursor.set_xdata([1000 * res.time[i]] * 2)
        if self.label_text is not None and self.animated:
            for t, v in zip(self.label_values, frame_label_values(res, i)):
                t.set_text(v)
        elif self.label_text is not None:
            self.label_text.set_text(frame_label(res, i))


LABEL_WIDTHS = (6, 6, 6, 6, 7)      # characters of each number of the frame label


def frame_label_template(res):
    """The frame label with a '{}' for each number (frame_label_values)."""
    r = res.bodies[res.root]
    return ("t = {} ms    head flexion {} deg ({} deg relative to %s), rotation {} deg    %s x displacement {} mm"
            % (r, r))


def frame_label_values(res, i):
    """The numbers of the frame label at sample i, each LABEL_WIDTHS wide:
    time [ms], head flexion and flexion relative to T1 [deg], head rotation
    [deg], T1's x displacement [mm]."""
    h, r = res.head, res.root
    dx = 1000 * (res.pos[i, r, 0] - res.pos[0, r, 0])
    v = (1000 * res.time[i], res.sagittal_angle(i, h), res.sagittal_angle(i, h, r), res.rotation_angle(i, h), dx)
    return ["%*.1f" % (w, x) for w, x in zip(LABEL_WIDTHS, v)]


def frame_label(res, i):
    """Time, head rotation and T1 displacement at sample i."""
    return frame_label_template(res).format(*frame_label_values(res, i))


def add_colourbars(fig, scene, axes):
    from matplotlib import cm
    for norm, cmap, label in ((scene.tension_norm, scene.tension_cmap, "ligament / muscle tension [N]"),
                              (scene.disc_norm, scene.disc_cmap, "disc axial force [N] (compression < 0)")):
        sm = cm.ScalarMappable(norm=norm, cmap=cmap)
        cb = fig.colorbar(sm, cax=axes.pop(0), orientation="horizontal")
        cb.set_label(label, fontsize=7)
        cb.ax.tick_params(labelsize=7)


def rotation_vector(q):
    """The rotation vector (axis times angle [rad]) of rotation matrices q (..., 3, 3)."""
    w = 0.5 * np.stack([q[..., 2, 1] - q[..., 1, 2], q[..., 0, 2] - q[..., 2, 0], q[..., 1, 0] - q[..., 0, 1]], -1)
    c = np.clip((np.trace(q, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arccos(c)
    sin = np.linalg.norm(w, axis=-1)
    scale = np.where(sin > 1e-12, angle / np.where(sin > 1e-12, sin, 1.0), 1.0)
    return w * scale[..., None]


def motion_components(res, first=0, last=None):
    """The head's motion relative to T1 (the root body) from sample first to
    last: (nt, 6) columns d_x, d_y, d_z, L phi_x, L phi_y, L phi_z [m]: d the
    head mass centre's displacement relative to T1's since the first sample,
    phi the rotation vector of the head's rotation relative to T1's since
    the first sample (in R), L the head's largest semi-axis (its uniform
    ellipsoid), so that a rotation counts as the travel of the head's rim."""
    last = len(res.time) - 1 if last is None else last
    h, r = res.head, res.root
    span = slice(first, last + 1)
    rel = res.pos[span, h] - res.pos[span, r]
    a = np.einsum("tij,kj->tik", res.rot[span, h], res.rot[first, h])      # S_h(t) S_h(0)^T
    b = np.einsum("tij,kj->tik", res.rot[span, r], res.rot[first, r])      # S_T1(t) S_T1(0)^T
    phi = rotation_vector(np.einsum("tji,tjk->tik", b, a))                 # B^T A
    size = float(np.max(ellipsoid_axes(res.mass[h], res.inertia[h])[0]))
    return np.hstack([rel - rel[0], size * phi])


def seen(view):
    """Columns of motion_components a plane view shows: the displacements
    along its two axes and the rotation about its normal."""
    i, j, n = PLANES[view]
    return {i, j, 3 + n}


def peak_norm(m, cols):
    """Peak over the samples of the norm of the columns `cols` of m."""
    cols = sorted(cols)
    return float(np.max(np.linalg.norm(m[:, cols], axis=1))) if cols else 0.0


def view_motion(res, first=0, last=None):
    """How much of the head's motion relative to T1 each plane view shows,
    {view: metres}: the peak norm of the motion components it shows."""
    m = motion_components(res, first, last)
    return {v: peak_norm(m, seen(v)) for v in PLANES}


def auto_views(res, first=0, last=None):
    """The plane views that show the head's motion relative to T1: first the
    one that shows the most (view_motion); then, while the components that
    no chosen view shows reach AUTO_SHARE of what the first shows, the view
    that shows the most of them. The side view when the head does not move."""
    m = motion_components(res, first, last)
    shown = {v: peak_norm(m, seen(v)) for v in PLANES}
    best = max(PLANES, key=lambda v: shown[v])
    if not shown[best] > 0:
        return ["side"]
    views, hidden = [best], set(range(6)) - seen(best)
    while len(views) < len(PLANES) and peak_norm(m, hidden) >= AUTO_SHARE * shown[best]:
        nxt = max((v for v in PLANES if v not in views), key=lambda v: peak_norm(m, seen(v) & hidden))
        views.append(nxt)
        hidden -= seen(nxt)
    return views


def parse_views(specs):
    """The views asked for by --view options (each a name or a comma list;
    'auto' anywhere means the automatic choice): a list of view names
    without repeats, or ['auto']. Raises ValueError on an unknown name."""
    names = [n.strip() for spec in (specs or ["auto"]) for n in spec.split(",") if n.strip()]
    bad = [n for n in names if n not in VIEWS + ("auto",)]
    if bad:
        raise ValueError("unknown view %s: the views are %s and auto" % (", ".join(bad), ", ".join(VIEWS)))
    if not names or "auto" in names:
        return ["auto"]
    return list(dict.fromkeys(names))


def resolve_views(res, views, frames, animation=False):
    """The views to draw: `views` from parse_views; 'auto' gives auto_views
    over the frames' span, and in an animation the 3-D view after them."""
    if views is None or list(views) == ["auto"]:
        picked = auto_views(res, int(frames[0]), int(frames[-1]))
        return picked + ["iso"] if animation else picked
    return list(views)


def build_figure(res, frames, dpi, fmax=None, rate_label="", views=("side", "front", "iso"), animated=False):
    """The animation figure: the views (side, front, top, iso) side by side,
    the head's angle about the first plane view's normal against time,
    colour bars; returns (fig, scene). animated: the Scene's fast path
    (fixed limits relative to T1, moving artists drawn over a background)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    w = 2 * round(12.0 * dpi / 2) / dpi                 # even pixel sizes (H.264)
    h = 2 * round(7.0 * dpi / 2) / dpi
    fig = plt.figure(figsize=(w, h), dpi=dpi)
    win = view_window(res, Geometry(res), frames[0], frames[-1])
    ext = win["hi"] - win["lo"]
    widths = {"side": ext[0], "front": max(ext[1], 0.5 * ext[0]), "top": ext[0], "iso": ext[2]}
    gs = fig.add_gridspec(2, 1, height_ratios=[3.3, 1], left=0.05, right=0.98, top=0.88, bottom=0.08, hspace=0.3)
    top = gs[0].subgridspec(1, len(views), width_ratios=[widths[v] for v in views], wspace=0.25)
    axes = {}
    for n, v in enumerate(views):
        axes[v] = fig.add_subplot(top[0, n], projection="3d" if v == "iso" else None)
        axes[v].set_title(TITLES[v], fontsize=8)
    bottom = gs[1].subgridspec(1, 3, wspace=0.25)
    hist = fig.add_subplot(bottom[0, 0:2])
    plane = next((v for v in views if v != "iso"), "side")
    t = 1000 * res.time
    hist.plot(t, [res.view_angle(i, res.head, plane) for i in range(len(t))], lw=1.2, label="head")
    hist.plot(t, [res.view_angle(i, res.root, plane) for i in range(len(t))], lw=1.0,
              label=res.bodies[res.root])
    hist.set_xlim(t[frames[0]], t[frames[-1]])
    hist.set_xlabel("time [ms]", fontsize=7)
    hist.set_ylabel({"side": "flexion [deg]", "front": "rotation about x [deg]",
                     "top": "rotation about z [deg]"}[plane], fontsize=7)
    hist.tick_params(labelsize=7)
    hist.legend(fontsize=7, loc="best")
    hist.grid(alpha=0.3)
    cbg = bottom[0, 2].subgridspec(2, 1, hspace=2.5)
    cax = [fig.add_subplot(cbg[0]), fig.add_subplot(cbg[1])]
    head = res.title + ("" if res.status in ("complete", "") else "  [run %s]" % res.status)
    fig.text(0.5, 0.975, head, ha="center", va="top", fontsize=9, weight="bold")
    label = fig.text(0.5, 0.945, "", ha="center", va="top", fontsize=8, family="monospace")
    fig.text(0.98, 0.012, rate_label, ha="right", fontsize=7)
    scene = Scene(res, frames, axes, fmax=fmax, history_ax=hist, label_text=label, animated=animated)
    add_colourbars(fig, scene, cax)
    return fig, scene


def animation_frames(res, start, end, fps, slow):
    """Sample indices of the frames: one every 1/(fps slow) s of model time."""
    t0 = res.time[0] if start is None else max(start, res.time[0])
    t1 = res.time[-1] if end is None else min(end, res.time[-1])
    dt = 1.0 / (fps * slow)
    n = int(np.floor((t1 - t0) / dt + 1e-9)) + 1
    return frame_indices(res.time, t0 + dt * np.arange(n))


class GifFrames:
    """GIF writer: the palette of the first frame (the whole figure, colour
    bars included: every colour a frame draws) made by Pillow's fast octree,
    each frame mapped to it as it comes, all written at close."""

    def __init__(self, out, fps):
        self.out, self.fps, self.frames, self.palette = out, fps, [], None

    def add(self, rgba):
        from PIL import Image
        h, w = rgba.shape[:2]
        im = Image.frombuffer("RGBA", (w, h), np.ascontiguousarray(rgba), "raw", "RGBA", 0, 1).convert("RGB")
        if self.palette is None:
            self.palette = im.quantize(256, method=Image.Quantize.FASTOCTREE)
        self.frames.append(im.quantize(palette=self.palette, dither=Image.Dither.NONE))

    def close(self):
        self.frames[0].save(self.out, save_all=True, append_images=self.frames[1:], loop=0,
                            duration=round(1000.0 / self.fps), optimize=False)


class Mp4Frames:
    """MP4 writer: raw RGBA frames piped to ffmpeg (H.264, yuv420p)."""

    def __init__(self, out, fps, size):
        import subprocess
        w, h = size
        self.proc = subprocess.Popen(
            ["ffmpeg", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgba", "-s", "%dx%d" % (w, h),
             "-r", "%g" % fps, "-i", "-", "-c:v", "libx264", "-pix_fmt", "yuv420p", out],
            stdin=subprocess.PIPE)

    def add(self, rgba):
        self.proc.stdin.write(np.ascontiguousarray(rgba).tobytes())

    def close(self):
        self.proc.stdin.close()
        if self.proc.wait() != 0:
            raise OSError("ffmpeg failed (exit %d)" % self.proc.returncode)


def write_animation(res, out, args):
    """Write the animation (GIF or MP4, from out's suffix): the figure drawn
    once whole, then each frame the moving artists drawn over that
    background (Scene's animated path) and the Agg buffer handed to the
    writer; returns (number of frames, views drawn)."""
    import matplotlib
    matplotlib.use("Agg")
    frames = animation_frames(res, args.start, args.end, args.fps, args.slow)
    views = resolve_views(res, args.views, frames, animation=True)
    rate = "real time" if args.slow == 1 else "slow motion %gx" % args.slow
    fig, scene = build_figure(res, frames, args.dpi, args.fmax,
                              "%s, %g frames/s, %d frames" % (rate, args.fps, len(frames)), views=views,
                              animated=True)
    from mpl_toolkits.mplot3d.art3d import Line3DCollection
    canvas = fig.canvas
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    size = canvas.get_width_height()
    writer = GifFrames(out, args.fps) if out.lower().endswith(".gif") else Mp4Frames(out, args.fps, size)
    try:
        for n, i in enumerate(frames):
            scene.update(i)
            canvas.restore_region(background)
            for owner, art in scene.moving:
                if isinstance(art, Line3DCollection):
                    art.do_3d_projection()         # a normal draw of the 3-D axes does this
                owner.draw_artist(art)
            writer.add(np.asarray(canvas.buffer_rgba()))
            if not args.quiet and (n % 25 == 0 or n == len(frames) - 1):
                print("hhneck-animate: frame %d of %d (t = %.1f ms)" % (n + 1, len(frames), 1000 * res.time[i]),
                      file=sys.stderr)
    finally:
        writer.close()
    import matplotlib.pyplot as plt
    plt.close(fig)
    return len(frames), views


def write_strip(res, out, every, dpi, fmax=None, start=None, end=None, views=None):
    """Key-frame strip: every `every` seconds, one block of rows of up to 7
    frames for each view (views: as resolve_views takes them, default
    auto); returns (number of key frames, views drawn)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t0 = res.time[0] if start is None else start
    t1 = res.time[-1] if end is None else min(end, res.time[-1])
    frames = frame_indices(res.time, np.arange(t0, t1 + 1e-9, every))
    views = resolve_views(res, views, frames)
    ncol = min(len(frames), 7)
    rows = -(-len(frames) // ncol)                      # rows of one view
    nrow = rows * len(views)
    fig = plt.figure(figsize=(2.2 * ncol + 1.0, 2.7 * nrow + 0.6), dpi=dpi)
    gs = fig.add_gridspec(nrow, ncol, wspace=0.05, hspace=0.3, left=0.01, right=0.88,
                          top=1 - 0.75 / (2.7 * nrow + 0.6), bottom=0.02)
    moves = np.ptp(res.pos[:, res.root, 0]) > 1e-3
    scene = None
    for b, view in enumerate(views):
        for n, i in enumerate(frames):
            ax = fig.add_subplot(gs[b * rows + n // ncol, n % ncol], projection="3d" if view == "iso" else None)
            scene = Scene(res, frames, {view: ax}, fmax=fmax)
            scene.update(i)
            if view == "iso":
                ax.set_xlabel(""); ax.set_ylabel(""); ax.set_zlabel("")
            else:
                ax.set_xticks([]); ax.set_yticks([]); ax.set_xlabel(""); ax.set_ylabel("")
            what = {"side": "head", "front": "head x-rot", "top": "head z-rot", "iso": "head rot"}[view]
            title = "%.0f ms  %s %+.0f deg" % (1000 * res.time[i], what, res.view_angle(i, res.head, view))
            if len(views) > 1:
                title = "%s  %s" % (view, title)
            if moves:
                dx = round(1000 * (res.pos[i, res.root, 0] - res.pos[0, res.root, 0])) + 0.0   # no "-0"
                title += "\n%s dx %+.0f mm" % (res.bodies[res.root], dx)
            ax.set_title(title, fontsize=8)
    fig.suptitle(res.title + " (%s views every %.0f ms, ground marks %.0f mm apart)"
                 % (", ".join(views), 1000 * every, 1000 * GROUND_STEP), fontsize=9)
    from matplotlib import cm
    for n, (norm, cmap, label) in enumerate(((scene.tension_norm, scene.tension_cmap, "tension [N]"),
                                             (scene.disc_norm, scene.disc_cmap, "disc axial [N]"))):
        cax = fig.add_axes([0.9 + 0.05 * n, 0.12, 0.012, 0.7])
        cb = fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax)
        cb.set_label(label, fontsize=7)
        cb.ax.tick_params(labelsize=6)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return len(frames), views


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-animate", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("result", help="hhneck HDF5 result file")
    p.add_argument("out", nargs="?", help="animation to write: NAME.gif, NAME.mp4, or NAME (NAME.mp4 when "
                                          "ffmpeg is installed, else NAME.gif)")
    p.add_argument("--slow", type=float, default=20.0,
                   help="slow-motion factor: 1 is real time, 20 (default) plays 1 ms of the run in 20 ms")
    p.add_argument("--fps", type=float, default=25.0, help="frames per second of the video (default 25)")
    p.add_argument("--start", type=float, help="first time drawn [s] (default: the file's first sample)")
    p.add_argument("--end", type=float, help="last time drawn [s] (default: the file's last sample)")
    p.add_argument("--dpi", type=float, default=80.0,
                   help="resolution: the frame is 12 x 7 inches, 960 x 560 pixels at the default 80")
    p.add_argument("--fmax", type=float,
                   help="tension at the top of the colour scale [N] (default: the peak between the first and last frame)")
    p.add_argument("--view", dest="views", action="append", metavar="VIEW",
                   help="side, front, top, iso or auto (default): repeat the option or give a comma list for "
                        "several; auto picks the plane views that show the head's motion relative to T1 "
                        "(the animation adds the 3-D view)")
    p.add_argument("--strip", metavar="PNG", help="also write a key-frame strip of the views")
    p.add_argument("--every", type=float, default=0.02, help="key-frame interval of the strip [s] (default 0.02)")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    args = p.parse_args(argv)
    if args.out is None and args.strip is None:
        p.error("give an output animation (OUT.gif or OUT.mp4) or --strip PNG")
    try:
        args.views = parse_views(args.views)
    except ValueError as e:
        p.error(str(e))
    if args.out is not None:
        if "." not in os.path.basename(args.out):         # no suffix: MP4 when ffmpeg is there, else GIF
            args.out += ".mp4" if shutil.which("ffmpeg") else ".gif"
        suffix = args.out.lower().rsplit(".", 1)[-1]
        if suffix not in ("gif", "mp4"):
            p.error("the animation must be NAME.gif, NAME.mp4 or NAME (MP4 when ffmpeg is installed, else GIF), "
                    "not %s" % args.out)
        if suffix == "mp4" and shutil.which("ffmpeg") is None:
            print("hhneck-animate: MP4 needs ffmpeg, which is not installed: install it "
                  "(sudo apt-get install ffmpeg) or ask for OUT.gif instead", file=sys.stderr)
            return 2
    if args.slow <= 0 or args.fps <= 0 or args.every <= 0:
        p.error("--slow, --fps and --every must be positive")
    res = Result(args.result)
    if args.out is not None:
        n, views = write_animation(res, args.out, args)
        print("hhneck-animate: wrote %s (%d frames), views: %s" % (args.out, n, ", ".join(views)))
    if args.strip is not None:
        n, views = write_strip(res, args.strip, args.every, min(args.dpi, 100.0) + 20, args.fmax, args.start,
                               args.end, args.views)
        print("hhneck-animate: wrote %s (%d key frames), views: %s" % (args.strip, n, ", ".join(views)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
