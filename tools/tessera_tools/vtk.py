# SPDX-License-Identifier: GPL-2.0-or-later
"""VTK files of the cell polygons, for ParaView and OVITO.

One unstructured-grid file (``.vtu``, written by meshio) per frame: every cell
is one polygon (z = 0 plane) with every numeric per-atom column of the dump as
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
(:mod:`tessera_tools.voronoi`).
"""

import json
import os
import xml.etree.ElementTree as ET

import numpy as np

from .dump import iter_dump
from .junctions import junction_tessellation, paired_frames
from .voronoi import tessellate_frame

VECTORS = {"velocity": ("vx", "vy", "vz"), "polarity": ("mux", "muy", "muz")}


def _meshio():
    try:
        import meshio
    except ImportError:
        raise RuntimeError("writing VTK needs meshio (Debian package python3-meshio: "
                           "apt-get install python3-meshio)") from None
    return meshio


def frame_mesh(frame, tess, time=None):
    """A meshio.Mesh of one frame's polygons with per-cell data (one cell block per polygon size)."""
    meshio = _meshio()
    n = len(tess)
    data = {}
    for name in frame.names:
        col = np.asarray(frame[name])
        if col.dtype.kind in "iuf" and len(col) == n:
            data[name] = col
    data["area"] = tess.area
    data["perimeter"] = tess.perimeter
    data["shape_index"] = tess.shape_index
    data["sides"] = tess.sides.astype(np.int64)
    for vec, comps in VECTORS.items():
        if all(c in frame for c in comps[:2]):
            cols = [np.asarray(frame[c], dtype=float) if c in frame else np.zeros(n) for c in comps]
            data[vec] = np.column_stack(cols)
    sizes = np.array([len(p) for p in tess.polygons], dtype=int)
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    points = np.zeros((offsets[-1], 3))
    if n:
        points[:, :2] = np.vstack(tess.polygons)
    cells, cell_data = [], {name: [] for name in data}
    for m in np.unique(sizes):
        members = np.nonzero(sizes == m)[0]
        conn = offsets[members][:, None] + np.arange(m)[None, :]
        cells.append(("polygon", conn))
        for name, values in data.items():
            cell_data[name].append(values[members])
    field_data = {} if time is None else {"TIME": np.array([float(time)])}
    return meshio.Mesh(points, cells, cell_data=cell_data, field_data=field_data)


def _frame_time(frame, dt):
    if frame.time is not None:
        return frame.time
    return frame.timestep * dt if dt is not None else float(frame.timestep)


def write_vtk(atoms_path, out_prefix, local_path=None, frames=None, dt=None, compute=None, progress=None):
    """Write ``{out_prefix}_{timestep}.vtu`` for the selected frames, ``{out_prefix}.pvd`` and
    ``{out_prefix}.vtu.series``; returns the list of .vtu paths.

    ``frames``: slice over the frames (over the timesteps common to both dumps with a local dump);
    ``dt``: time per step for the time values (default: the dump's TIME item, else the timestep);
    ``progress``: a callable wrapping an iterable (e.g. tqdm) or None."""
    if local_path:
        pairs = paired_frames(atoms_path, local_path, frames)
        work = [(a, lambda a=a, l=l: junction_tessellation(a, l, compute)) for a, l in pairs]
    else:
        chosen = list(iter_dump(atoms_path))
        chosen = chosen[frames] if frames is not None else chosen
        if not chosen:
            raise ValueError(f"{atoms_path}: no frames selected")
        work = [(a, lambda a=a: tessellate_frame(a)) for a in chosen]
    directory = os.path.dirname(out_prefix)
    if directory:
        os.makedirs(directory, exist_ok=True)
    width = max(len(str(a.timestep)) for a, _ in work)
    written, entries = [], []
    iterable = progress(work) if progress else work
    for frame, make in iterable:
        tess = make()
        time = _frame_time(frame, dt)
        path = f"{out_prefix}_{frame.timestep:0{width}d}.vtu"
        frame_mesh(frame, tess, time).write(path)
        written.append(path)
        entries.append((time, os.path.basename(path)))
    _write_pvd(out_prefix + ".pvd", entries)
    with open(out_prefix + ".vtu.series", "w") as f:
        json.dump({"file-series-version": "1.0",
                   "files": [{"name": name, "time": t} for t, name in entries]}, f, indent=1)
    return written


def _write_pvd(path, entries):
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    coll = ET.SubElement(root, "Collection")
    for t, name in entries:
        ET.SubElement(coll, "DataSet", timestep=repr(float(t)), group="", part="0", file=name)
    ET.indent(root) if hasattr(ET, "indent") else None
    ET.ElementTree(root).write(path, xml_declaration=True, encoding="utf-8")
