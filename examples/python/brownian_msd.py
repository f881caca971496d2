#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Free Brownian particles driven from Python: mean-square displacement
against the Einstein prediction 4 D t, D = kT / gamma_t (2d).

    /usr/bin/python3 brownian_msd.py
    mpirun -np 2 /usr/bin/python3 brownian_msd.py --steps 2000
"""

import argparse
import os
import sys

from lammps import lammps, LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tessera_lammps  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--atoms", type=int, default=4000)
    parser.add_argument("--temp", type=float, default=1.0)
    parser.add_argument("--gamma-t", type=float, default=2.0)
    parser.add_argument("--dt", type=float, default=0.01)
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--blocks", type=int, default=10, help="MSD reported this many times")
    parser.add_argument("--rng", choices=["uniform", "gaussian"], default="uniform")
    parser.add_argument("--log", default="none", help="LAMMPS log file (default none)")
    opts = parser.parse_args()

    lmp = lammps(cmdargs=["-log", opts.log, "-screen", "none", "-nocite"])
    tessera_lammps.register(lmp)
    me = lmp.extract_setting("world_rank")

    lmp.commands_string(f"""
units           lj
dimension       2
atom_style      atomic
boundary        p p p
region          box block 0 100 0 100 -0.5 0.5
create_box      1 box
create_atoms    1 random {opts.atoms} 5871 box
mass            1 1.0
pair_style      zero 1.0
pair_coeff      * *
fix             move all brownian {opts.temp} 12908410 gamma_t {opts.gamma_t} rng {opts.rng}
compute         msd all msd
thermo_style    custom step c_msd[4]
timestep        {opts.dt}
""")
    block = max(opts.steps // opts.blocks, 1)
    lmp.command(f"thermo {block}")
    diffusion = opts.temp / opts.gamma_t
    if me == 0:
        print(f"# {opts.atoms} free particles, D = kT/gamma_t = {diffusion:g}, rng {opts.rng}")
        print(f"# {'time':>8} {'MSD':>12} {'4 D t':>12} {'ratio':>8}")
    lmp.command("run 0")
    for _ in range(opts.blocks):
        lmp.command(f"run {block}")
        t = lmp.get_thermo("step") * opts.dt
        msd = lmp.extract_compute("msd", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)[3]
        if me == 0:
            print(f"  {t:8.3f} {msd:12.6g} {4 * diffusion * t:12.6g} {msd / (4 * diffusion * t):8.4f}")
    lmp.close()


if __name__ == "__main__":
    main()
