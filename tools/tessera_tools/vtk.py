# SPDX-License-Identifier: GPL-2.0-or-later
"""VTK files of the cells, for ParaView and OVITO, for every model.

One unstructured-grid file (``.vtu``, written by meshio) per frame: in 2d every
cell is one polygon (z = 0 plane) with every numeric per-atom column of the dump as
cell data (``id``, ``type``, ``c_cell[1]`` ...), plus the polygon's own
``area``, ``perimeter``, ``shape_index`` and ``sides``, and the vectors
``velocity`` (vx vy vz) and ``polarity`` (mux muy muz) when the dump has them.
A ParaView collection (``.pvd``) and a ParaView file series
(``.vtu.series``) list the frames with their times, so the frames open as one
time series; OVITO imports the ``.vtu`` files (File > Load File, with the
wildcard of the frame names).

The polygons are those of a ``dump local`` of ``compute vertex/local`` when
given (the tessellation LAMMPS computed, to the dump's printed precision);
otherwise the periodic Voronoi tessellation of the dumped centres
(:mod:`tessera_tools.voronoi`), which needs a box periodic in x and y.  Finite
cells (free arcs: rows with neighbour ID 0) are polygons with their arcs
sampled (:data:`tessera_tools.junctions.ARC_STEP`), in open boxes too; their
``area``, ``perimeter`` and ``shape_index`` are the exact ones (arcs, not
the samples' chords).  Without a local dump, ``radius`` gives the finite
Voronoi cells of the dumped centres (:mod:`tessera_tools.finite`).

Atoms that are no cells (particles: obstacles, beads; the atoms whose type is not
among ``cell_types``) are never tessellated: they go to a second series of files,
``PREFIX_particles_<timestep>.vtu`` (one VTK vertex per particle, every numeric
per-atom column as point data, ``velocity`` and ``polarity`` vectors as for the
cells) with its own ``PREFIX_particles.pvd`` and ``.vtu.series``; a frame without
particles gives a file with no points, so the two series keep the same frames.

Cells on a sphere (a local dump with 9 columns and one row per cell and
neighbour: geodesic edges) are polygons of their Voronoi vertices in space
(:mod:`tessera_tools.sphere_cells`), with their spherical ``area``.

In 3d (a local dump with the 9 columns of 3d rows) every cell is one
``VTK_POLYHEDRON`` made of its face polygons (the rows with the same cell and
neighbour IDs, chained edge to edge, outward), with the per-atom columns and
its ``volume``, ``surface`` and ``faces`` as cell data.
"""

import json
import os
import xml.etree.ElementTree as ET

import numpy as np

from .dump import iter_dump, selects
from .junctions import face_cycles, junction_columns, junction_tessellation, paired_frames
from .voronoi import tessellate_frame

VECTORS = {"velocity": ("vx", "vy", "vz"), "polarity": ("mux", "muy", "muz")}


def _meshio():
    try:
        import meshio
    except ImportError:
        raise RuntimeError("writing VTK needs meshio (Debian package python3-meshio: "
                           "apt-get install python3-meshio)") from None
    return meshio


def frame_columns(frame, n):
    """The frame's numeric per-atom columns (each of length n), by name."""
    data = {}
    for name in frame.names:
        col = np.asarray(frame[name])
        if col.dtype.kind in "iuf" and len(col) == n:
            data[name] = col
    return data


def cells_mesh(points, sizes, data, block, time=None):
    """A meshio.Mesh with one cell block per number of corners (ascending, the order in which
    meshio reads them back): block(members, m, offsets) gives the (type, connectivity) of the
    cells ``members`` with m corners each, their corners stored from ``offsets[members]``;
    ``data`` holds the per-cell arrays and ``time`` the TIME field."""
    meshio = _meshio()
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    blocks, cell_data = [], {name: [] for name in data}
    for m in np.unique(sizes):
        members = np.nonzero(sizes == m)[0]
        blocks.append(block(members, m, offsets))
        for name, values in data.items():
            cell_data[name].append(values[members])
    field_data = {} if time is None else {"TIME": np.array([float(time)])}
    return meshio.Mesh(points, blocks, cell_data=cell_data, field_data=field_data)


def polygon_block(members, m, offsets):
    """cells_mesh's block of polygons whose corners are stored one after another."""
    return ("polygon", offsets[members][:, None] + np.arange(m)[None, :])


def frame_mesh(frame, tess, time=None):
    """A meshio.Mesh of one frame's polygons with per-cell data (one cell block per polygon size)."""
    n = len(tess)
    data = frame_columns(frame, n)
    data["area"] = tess.area
    data["perimeter"] = tess.perimeter
    data["shape_index"] = tess.shape_index
    data["sides"] = tess.sides.astype(np.int64)
    for vec, comps in VECTORS.items():
        if all(c in frame for c in comps[:2]):
            cols = [np.asarray(frame[c], dtype=float) if c in frame else np.zeros(n) for c in comps]
            data[vec] = np.column_stack(cols)
    sizes = np.array([len(p) for p in tess.polygons], dtype=int)
    points = np.zeros((sizes.sum(), 3))
    if n:
        points[:, :2] = np.vstack(tess.polygons)
    return cells_mesh(points, sizes, data, polygon_block, time)


class Cells3d:
    """The polyhedra of a 3d frame from the rows of compute vertex/local: ``ids`` (the atom
    frame's order), per cell ``vertices`` (m, 3) and ``faces`` (lists of vertex index arrays,
    counter-clockwise seen from outside), ``volume``, ``surface`` and ``nfaces`` arrays.
    Each cell is shifted by a whole box vector next to its position in the atom frame."""

    def __init__(self, ids, vertices, faces):
        self.ids = ids
        self.vertices = vertices
        self.faces = faces
        self.volume = np.array([polyhedron_volume(v, f) for v, f in zip(vertices, faces)])
        self.surface = np.array([sum(_polygon_area3(v[q]) for q in f) for v, f in zip(vertices, faces)])
        self.nfaces = np.array([len(f) for f in faces], dtype=np.int64)

    def __len__(self):
        return len(self.ids)


def polyhedron_volume(vertices, faces):
    """Volume enclosed by outward face polygons (divergence theorem, fan from each face's first corner)."""
    v = np.asarray(vertices, dtype=float)
    total = 0.0
    for f in faces:
        p = v[np.asarray(f)]
        for k in range(1, len(p) - 1):
            total += np.dot(p[0], np.cross(p[k], p[k + 1]))
    return total / 6.0


def _polygon_area3(p):
    p = np.asarray(p, dtype=float)
    s = np.zeros(3)
    for k in range(1, len(p) - 1):
        s += np.cross(p[k] - p[0], p[k + 1] - p[0])
    return 0.5 * float(np.linalg.norm(s))


def _positions3(frame):
    for names in (("x", "y", "z"), ("xu", "yu", "zu")):
        if all(n in frame for n in names):
            return np.column_stack([frame[n] for n in names]).astype(float)
    raise KeyError("a 3d atom dump needs positions x y z (or xu yu zu)")


def _minimum_image3(box, d):
    """Shortest periodic representative of 3d displacements ``d`` (N, 3)."""
    m = np.array([[box.lx, box.xy, box.xz], [0.0, box.ly, box.yz], [0.0, 0.0, box.zhi - box.zlo]])
    s = np.linalg.solve(m, np.asarray(d, dtype=float).T).T
    for k in range(3):
        if box.periodic[k]:
            s[:, k] -= np.round(s[:, k])
    return s @ m.T


def frame_cells3d(atoms, local, compute=None):
    """:class:`Cells3d` of the atom frame ``atoms`` from the local frame ``local`` (same timestep)."""
    if atoms.timestep != local.timestep:
        raise ValueError(f"atom frame at timestep {atoms.timestep} paired with a local frame at {local.timestep}")
    names = junction_columns(local, compute)
    if len(names) != 9:
        raise ValueError("frame_cells3d needs the 9 columns of a 3d local dump (compute vertex/local in 3d)")
    cell = np.asarray(local[names[0]]).astype(np.int64)
    other = np.asarray(local[names[1]]).astype(np.int64)
    start = np.column_stack([local[n] for n in names[2:5]]).astype(float)
    end = np.column_stack([local[n] for n in names[5:8]]).astype(float)
    ids = np.asarray(atoms.ids).astype(np.int64)
    index = {int(i): k for k, i in enumerate(ids)}
    missing = sorted(set(cell.tolist()) - set(index))
    if missing:
        raise ValueError(f"timestep {atoms.timestep}: the local dump has faces of cells {missing[:5]} "
                         "that are not in the atom dump")
    without = sorted(set(index) - set(cell.tolist()))
    if without:
        raise ValueError(f"timestep {atoms.timestep}: cells {without[:5]} of the atom dump have no face rows "
                         "(was compute vertex/local defined on a smaller group?)")
    centres = _positions3(atoms)
    rows_of = [[] for _ in ids]
    for k, c in enumerate(cell.tolist()):
        rows_of[index[c]].append(k)
    vertices, faces = [], []
    for i, rows in enumerate(rows_of):
        rows = np.array(rows, dtype=int)
        by_neighbour = {}
        for k in rows:
            by_neighbour.setdefault(int(other[k]), []).append(k)
        corner = {}
        verts, cell_faces = [], []
        for group in by_neighbour.values():
            group = np.array(group)
            for cyc in face_cycles(start[group], end[group]):
                face = []
                for k in group[cyc]:
                    key = tuple(start[k])
                    if key not in corner:
                        corner[key] = len(verts)
                        verts.append(start[k])
                    face.append(corner[key])
                cell_faces.append(np.array(face, dtype=np.int64))
        verts = np.array(verts)
        mid = verts.mean(axis=0)
        d = (centres[i] - mid)[None, :]
        verts = verts + (d - _minimum_image3(atoms.box, d))[0]
        vertices.append(verts)
        faces.append(cell_faces)
    return Cells3d(ids, vertices, faces)


def frame_mesh3d(frame, cells, time=None):
    """A meshio.Mesh of one 3d frame: one polyhedron per cell (blocks by number of corners,
    ascending, the order in which meshio reads them back) with per-cell data."""
    n = len(cells)
    data = frame_columns(frame, n)
    data["volume"] = cells.volume
    data["surface"] = cells.surface
    data["faces"] = cells.nfaces
    for vec, comps in VECTORS.items():
        if all(c in frame for c in comps):
            data[vec] = np.column_stack([np.asarray(frame[c], dtype=float) for c in comps])
    sizes = np.array([len(v) for v in cells.vertices], dtype=int)
    points = np.vstack(cells.vertices) if n else np.zeros((0, 3))

    def polyhedra(members, m, offsets):
        return (f"polyhedron{m}", [[offsets[i] + f for f in cells.faces[i]] for i in members])

    return cells_mesh(points, sizes, data, polyhedra, time)


def particles_mesh(particles, time=None):
    """A meshio.Mesh of the atoms that are no cells: one vertex cell per atom, at its position
    wrapped into the box in x and y (z as dumped, else 0), every numeric column as point data."""
    meshio = _meshio()
    n = particles.natoms
    points = np.zeros((n, 3))
    if n:
        points[:, :2] = particles.positions()       # wrapped into the box, as the cells
        if "z" in particles:
            points[:, 2] = np.asarray(particles["z"], dtype=float)
    data = frame_columns(particles, n)
    for vec, comps in VECTORS.items():
        if all(c in particles for c in comps[:2]):
            data[vec] = np.column_stack([np.asarray(particles[c], dtype=float) if c in particles
                                         else np.zeros(n) for c in comps])
    field_data = {} if time is None else {"TIME": np.array([float(time)])}
    return meshio.Mesh(points, [("vertex", np.arange(n, dtype=np.int64)[:, None])], point_data=data,
                       field_data=field_data)


def _frame_time(frame, dt):
    if frame.time is not None:
        return frame.time
    return frame.timestep * dt if dt is not None else float(frame.timestep)


def write_vtk(atoms_path, out_prefix, local_path=None, frames=None, dt=None, compute=None, progress=None,
              radius=None, cell_types=None):
    """Write ``{out_prefix}_{timestep}.vtu`` for the selected frames, ``{out_prefix}.pvd`` and
    ``{out_prefix}.vtu.series``; returns the list of .vtu paths.

    ``frames``: slice over the frames (over the timesteps common to both dumps with a local dump);
    ``dt``: time per step for the time values (default: the dump's TIME item, else the timestep);
    ``progress``: a callable wrapping an iterable (e.g. tqdm) or None; ``radius``: without a
    local dump, the finite Voronoi cells of that radius (any box) instead of the periodic
    Voronoi tessellation; ``cell_types`` (a set from :func:`tessera_tools.dump.parse_types`):
    the atoms of other types are particles, written to ``{out_prefix}_particles_{timestep}.vtu``
    (listed in ``{out_prefix}_particles.pvd``) instead of being tessellated."""
    if local_path:
        pairs = paired_frames(atoms_path, local_path, frames, cell_types)
        from .sphere_cells import is_sphere_local, frame_sphere_cells

        if is_sphere_local(pairs[0][1], compute):    # cells on a sphere: one row per edge
            work = [(a, lambda a=a, l=l: frame_sphere_cells(a, l, compute)) for a, l in pairs]
        elif len(junction_columns(pairs[0][1], compute)) == 9:
            work = [(a, lambda a=a, l=l: frame_cells3d(a, l, compute)) for a, l in pairs]
        else:
            work = [(a, lambda a=a, l=l: junction_tessellation(a, l, compute)) for a, l in pairs]
    else:
        chosen = list(iter_dump(atoms_path, cell_types))
        chosen = chosen[frames] if frames is not None else chosen
        if not chosen:
            raise ValueError(f"{atoms_path}: no frames selected")
        if "z" in chosen[0] and np.ptp(np.asarray(chosen[0]["z"], dtype=float)) > 0:
            raise ValueError(f"{atoms_path}: the cells' z differ (a 3d tissue?); 3d cells are written only "
                             "from a dump local of compute vertex/local: give it with --local")
        if radius:
            from .finite import finite_voronoi

            work = [(a, lambda a=a: finite_voronoi(a.positions(), a.box, radius, a.ids)) for a in chosen]
        elif not (chosen[0].box.periodic[0] and chosen[0].box.periodic[1]):
            raise ValueError(f"{atoms_path}: the box is not periodic in x and y, so the cells cannot be "
                             "re-tessellated from the centres; give the cells LAMMPS computed with "
                             "--local (a dump local of compute vertex/local, e.g. 'compute l all "
                             "vertex/local' and 'dump 2 all local N cells.local c_l[*]'), or for finite "
                             "cells their radius with --radius")
        else:
            work = [(a, lambda a=a: tessellate_frame(a)) for a in chosen]
    directory = os.path.dirname(out_prefix)
    if directory:
        os.makedirs(directory, exist_ok=True)
    width = max(len(str(a.timestep)) for a, _ in work)
    written, entries, particle_entries = [], [], []
    iterable = progress(work) if progress else work
    for frame, make in iterable:
        tess = make()
        time = _frame_time(frame, dt)
        path = f"{out_prefix}_{frame.timestep:0{width}d}.vtu"
        from .sphere_cells import SphereCells, frame_mesh_sphere

        if isinstance(tess, SphereCells):
            mesh = frame_mesh_sphere(frame, tess, VECTORS, time)
        elif isinstance(tess, Cells3d):
            mesh = frame_mesh3d(frame, tess, time)
        else:
            mesh = frame_mesh(frame, tess, time)
        mesh.write(path)
        written.append(path)
        entries.append((time, os.path.basename(path)))
        if frame.particles is not None:
            ppath = f"{out_prefix}_particles_{frame.timestep:0{width}d}.vtu"
            particles_mesh(frame.particles, time).write(ppath)
            particle_entries.append((time, os.path.basename(ppath)))
    _write_series(out_prefix, entries)
    if selects(cell_types):
        _write_series(out_prefix + "_particles", particle_entries)
    return written


def _write_series(prefix, entries):
    """``prefix.pvd`` and ``prefix.vtu.series``: the files of ``entries`` (time, name) as a time series."""
    _write_pvd(prefix + ".pvd", entries)
    with open(prefix + ".vtu.series", "w") as f:
        json.dump({"file-series-version": "1.0",
                   "files": [{"name": name, "time": t} for t, name in entries]}, f, indent=1)


def _write_pvd(path, entries):
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    coll = ET.SubElement(root, "Collection")
    for t, name in entries:
        ET.SubElement(coll, "DataSet", timestep=repr(float(t)), group="", part="0", file=name)
    ET.indent(root) if hasattr(ET, "indent") else None
    ET.ElementTree(root).write(path, xml_declaration=True, encoding="utf-8")
