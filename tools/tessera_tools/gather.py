# SPDX-License-Identifier: GPL-2.0-or-later
"""Every rank's per-cell values and junction rows in a Python-driven LAMMPS, on any number of
MPI ranks, without mpi4py.

In a run on several ranks, ``lmp.extract_atom`` / ``lmp.extract_compute`` give each rank only
the atoms (or the local rows of compute vertex/local) it owns.  LAMMPS's own
``lmp.gather_atoms`` / ``lmp.gather`` collect per-atom data in atom-ID order but need the IDs
to be 1..N without gaps, which fix cell/divide and fix cell/death break.  These helpers work
with the library calls of both Debian's python3-lammps (2021) and current LAMMPS:

* :func:`gather_per_atom` -- per-atom data of all atoms (``x``, ``mu``, ``c_ID`` of compute
  vertex/atom, ``f_ID``, ``d_name``), sorted by atom ID, on every rank (``gather_concat``);
* :func:`gather_local` -- the rows of a local compute (compute vertex/local's junctions) of
  all ranks, on every rank, sorted; LAMMPS has no library call for local data, so LAMMPS
  itself writes them (``write_dump ... local``, which gathers to rank 0) to a file in
  ``directory`` that every rank then reads.

Call them on every rank (they are collective, like the LAMMPS commands).
"""

import os

import numpy as np

_calls = [0]
# Per-atom arrays of LAMMPS and their columns (gather_concat reads whole rows).
_COLUMNS = {"x": 3, "v": 3, "f": 3, "mu": 4, "omega": 3, "angmom": 3, "torque": 3}


def _array(data, n, count, dtype):
    return np.ctypeslib.as_array(data, shape=(n * count,)).astype(dtype).reshape(n, count) if n else \
        np.zeros((0, count), dtype=dtype)


def gather_per_atom(lmp, name, count=1, integer=False):
    """(ids, values) of all atoms of the system, sorted by atom ID, on every rank.

    name: a per-atom property ("x", "mu", "type", ...) or "c_ID" / "f_ID", "d_name" / "i_name"
    of fix property/atom.  count: all its columns (1 for a vector; x, v, f: 3; mu: 4, i.e.
    mux muy muz |mu|; compute vertex/atom: 9): LAMMPS reads the rows of an array as count
    values each, so a smaller count would mix rows.  integer: the values are integers (type,
    id, i_name).  values has shape (N, count).
    """
    if name in _COLUMNS and count != _COLUMNS[name]:
        raise ValueError(f"gather_per_atom: '{name}' has {_COLUMNS[name]} columns per atom; pass "
                         f"count={_COLUMNS[name]}, not {count} (take the columns you need from the result)")
    n = int(lmp.get_natoms())
    ids = np.asarray(_array(lmp.gather_atoms_concat("id", 0, 1), n, 1, np.int64))[:, 0]
    values = _array(lmp.gather_concat(name, 0 if integer else 1, count), n, count,
                    np.int64 if integer else float)
    order = np.argsort(ids, kind="stable")
    return ids[order], values[order]


def gather_local(lmp, compute_id, ncols, directory=".", keep=False):
    """All rows of the local compute ``compute_id`` (ncols columns; compute vertex/local: 7) of
    every rank, as an (M, ncols) array on every rank, sorted row-wise (by the first column,
    then the next, ...), so that the result does not depend on how the atoms are spread over
    the ranks.  The values are those of the current step (as a dump local would write them),
    at full precision.

    LAMMPS writes them with ``write_dump all local`` to a file in ``directory`` (default: the
    working directory, which every rank must see; the name holds the step and a call count,
    the file is removed afterwards unless keep=True).

    No dump needs to use the compute: the compute is invoked first through the library
    (``extract_compute``, which runs it when it is not current at this step), because a
    ``write_dump`` between runs of a compute that nothing invoked at the last step is an
    error of LAMMPS ("not current"), which under ``-screen none`` ends the process with
    status 1 and no message.  The compute still needs the cells of a run: call this after
    ``run`` (``run 0`` is enough), not before the first one."""
    _invoke_local(lmp, compute_id, ncols)
    step = int(lmp.extract_global("ntimestep"))
    nranks = int(lmp.extract_setting("world_size"))
    me = int(lmp.extract_setting("world_rank"))
    _calls[0] += 1
    path = os.path.join(directory, f".tessera-local-{compute_id}-{step}-{_calls[0]}-{nranks}.txt")
    cols = " ".join(f"c_{compute_id}[{k}]" for k in range(1, ncols + 1)) if ncols > 1 else f"c_{compute_id}"
    lmp.command(f"write_dump all local {path} {cols} modify format float %.17g")
    _barrier(lmp)    # rank 0 has written and closed the file
    rows = []
    with open(path) as f:
        lines = f.read().split("\n")
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: NUMBER OF ENTRIES"):
            nrows = int(lines[k + 1])
        if lines[k].startswith("ITEM: ENTRIES"):
            rows = [[float(v) for v in line.split()] for line in lines[k + 1:k + 1 + nrows]]
            break
        k += 1
    _barrier(lmp)    # every rank has read it
    if me == 0 and not keep:
        os.remove(path)
    a = np.array(rows, dtype=float).reshape(-1, ncols)
    return a[np.lexsort(a.T[::-1])] if len(a) else a


# lammps.LMP_STYLE_LOCAL, LMP_SIZE_ROWS, LMP_SIZE_COLS (the same numbers in every version)
_LOCAL, _ROWS, _COLS = 2, 4, 5


def _invoke_local(lmp, compute_id, ncols):
    """Run the local compute at the current step (if nothing did) through the library, so that
    write_dump finds it current, and check its column count.  Collective: compute
    vertex/loops gathers to rank 0 inside."""
    why = "there is no compute of that ID with local data"
    try:
        rows = lmp.extract_compute(compute_id, _LOCAL, _ROWS)
        cols = lmp.extract_compute(compute_id, _LOCAL, _COLS)
    except Exception as err:
        # a LAMMPS built with exceptions raises its own message; older python modules read the
        # NULL of a missing compute (ValueError "NULL pointer access")
        rows = None
        if "NULL" not in str(err):
            why = str(err).strip()
    if rows is None:
        raise ValueError(f"gather_local: compute '{compute_id}': {why}. Define a local compute before gathering "
                         f"(e.g. 'compute {compute_id} all vertex/local' or vertex/loops) and gather after a run "
                         "('run 0' is enough)")
    have = max(int(cols), 1)      # 0 columns: a local vector
    if have != ncols:
        raise ValueError(f"gather_local: compute '{compute_id}' has {have} local column(s), not ncols={ncols}; "
                         f"pass {have} (compute vertex/local: 7 in 2d, 9 in 3d; vertex/loops: 7)")


def _barrier(lmp):
    """A collective library call, so that no rank passes it before rank 0 reached it."""
    lmp.gather_atoms_concat("id", 0, 1)
