#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""An active tissue driven from Python: Debian's python3-lammps runs Tessera's
pair_style vertex/voronoi, fix polarity and compute vertex/atom; every block of
steps Python reads the per-cell shape index and polarity as numpy arrays and
prints the mean shape index and the polar order it computes itself, next to
the values LAMMPS computes (compute vertex/tissue, fix polarity; they agree).

    /usr/bin/python3 examples/python/tissue.py [--cells-x 10] [--steps 200] [--blocks 5]
    mpirun -np 2 /usr/bin/python3 examples/python/tissue.py
"""

import argparse
import os
import sys

import numpy as np
from lammps import lammps, LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tessera_lammps  # noqa: E402
from tessera_tools.gather import gather_per_atom  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells-x", type=int, default=10, help="lattice cells along x (2 per cell)")
    parser.add_argument("--steps", type=int, default=200, help="steps per block")
    parser.add_argument("--blocks", type=int, default=5)
    parser.add_argument("--p0", type=float, default=3.9, help="target shape index")
    args = parser.parse_args()

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none"])
    tessera_lammps.register(lmp)
    nx = args.cells_x
    lmp.commands_string(f"""
dimension 2
units lj
atom_style dipole
boundary p p p
lattice hex 1.0
region box block 0 {nx} 0 {nx // 2} -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
displace_atoms all random 0.1 0.1 0 4821 units box
pair_style vertex/voronoi 3.5
pair_coeff * * quadratic 1.0 1.0 1.0 {args.p0}
timestep 0.01
fix move all brownian 1.0 1 gamma_t 1.0 rng none
fix act all polarity 0.1 1.0 neighbor 1.0 noise 0.5 2711
compute cell all vertex/atom
compute tissue all vertex/tissue
thermo_style custom step pe c_tissue[1] f_act[1]
run 0
""")
    me = lmp.extract_setting("world_rank") if hasattr(lmp, "extract_setting") else 0
    if me == 0:
        print("# step  mean_q(python)  mean_q(lammps)  polar_order(python)  polar_order(lammps)")
    for _ in range(args.blocks):
        lmp.command(f"run {args.steps}")
        # per-atom data of all atoms on every rank, sorted by atom ID (works on any number of
        # ranks, also when fix cell/divide or cell/death leave gaps in the IDs, which
        # LAMMPS's own lmp.gather_atoms refuses); tessera_tools.gather.gather_local does
        # the same for the junction rows of compute vertex/local
        _, mu = gather_per_atom(lmp, "mu", 4)    # mux muy muz |mu|
        # the 9 per-cell columns of compute vertex/atom, from all ranks
        _, cells = gather_per_atom(lmp, "c_cell", 9)
        q = cells[:, 2]
        n = mu[:, :2] / np.linalg.norm(mu[:, :2], axis=1)[:, None]
        polar = float(np.hypot(*n.mean(axis=0)))
        q_lammps = lmp.extract_compute("tissue", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)[0]
        polar_lammps = lmp.extract_fix("act", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, 0)
        if me == 0:
            print("%6d  %.6f  %.6f  %.6f  %.6f" % (lmp.get_thermo("step"), q.mean(), q_lammps,
                                                   polar, polar_lammps))
    lmp.close()


if __name__ == "__main__":
    main()
