#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Feature-matrix checks of what the computes hand to other LAMMPS commands
(mixed into test_feature_matrix.FeatureMatrix):

variables  an atom-style variable of each per-cell column of compute
           vertex/atom (v = c_ID[I]) equals the column itself, atom by atom
           in a dump and summed by compute reduce;
t1_births  cells divide and die in a tissue that does not move (the vertex
           model: divide only, as its dying cells leave by moving): compute
           vertex/tissue's neighbour exchanges (element 3) equal, step by
           step, the new neighbour pairs counted here from dumped junctions
           among cells that existed at both steps and whose neighbourhoods
           no birth or death changed -- 0 in a still tissue."""

import numpy as np

from feature_models import dim_of, local_rows, model_script, printed

NCOLS = 9


def neighbour_pairs(rows, d, sphere):
    """The neighbour pairs (i < j) of one frame of compute vertex/local rows:
    a junction (2d edge length, 3d face area, column 7 or 9) counts if it
    exceeds 1e-9 of the cell's mean junction; free arcs (neighbour 0) do not."""
    size = rows[:, 6] if d == 2 and not sphere else rows[:, 8]
    cell, nb = rows[:, 0].astype(int), rows[:, 1].astype(int)
    pairs = set()
    for c in set(cell.tolist()):
        mine = (cell == c) & (nb > 0)
        if not mine.any():
            continue
        floor = 1e-9 * size[mine].mean()
        for j, s in zip(nb[mine], size[mine]):
            if s > floor:
                pairs.add((min(c, int(j)), max(c, int(j))))
    return pairs


def exchanges(before, after, ids_before, ids_after):
    """New pairs between two frames among cells that exist in both and whose
    neighbourhood no event touched (a neighbour now that did not exist
    before, or a neighbour before that no longer exists); and all new pairs
    among cells that exist in both, touched or not."""
    old, new = set(ids_before), set(ids_after)
    nbr_before, nbr_after = {}, {}
    for i, j in before:
        nbr_before.setdefault(i, set()).add(j)
        nbr_before.setdefault(j, set()).add(i)
    for i, j in after:
        nbr_after.setdefault(i, set()).add(j)
        nbr_after.setdefault(j, set()).add(i)
    touched = {c for c in new if any(n not in old for n in nbr_after.get(c, ()))}
    touched |= {c for c in old & new if any(n not in new for n in nbr_before.get(c, ()))}
    gained = [(i, j) for i, j in after - before if i in old and j in old]
    clean = [(i, j) for i, j in gained if i not in touched and j not in touched]
    return len(clean), len(gained)


class OutputChecks:

    def check_variables(self, model):
        # a few Brownian steps, so that velocities (coordination, orientation)
        # and edges vary from cell to cell
        variables = "".join(f"variable v{k} atom c_c[{k}]\n" for k in range(1, NCOLS + 1))
        vcols = " ".join(f"v_v{k}" for k in range(1, NCOLS + 1))
        ccols = " ".join(f"c_c[{k}]" for k in range(1, NCOLS + 1))
        script = model_script(model) + f"""fix p all polarity 0.3 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.005
compute c all vertex/atom
{variables}compute vs all reduce sum {vcols}
compute cs all reduce sum {ccols}
thermo_style custom step pe c_vs[*] c_cs[*]
dump d all custom 3 cols.dump id {vcols} {ccols}
dump_modify d format float %.17g
run 3
print "S $(c_vs[1]:%.17g) $(c_vs[4]:%.17g) $(c_vs[9]:%.17g) $(c_cs[1]:%.17g) $(c_cs[4]:%.17g) $(c_cs[9]:%.17g)"
"""
        run = self.run_lmp(script)
        frames = run.dump("cols.dump")
        self.assertEqual(len(frames), 2)
        for f in frames:
            for k in range(1, NCOLS + 1):
                np.testing.assert_array_equal(f[f"v_v{k}"], f[f"c_c[{k}]"], err_msg=f"column {k}")
        f = frames[-1]
        self.assertGreater(np.ptp(f["c_c[1]"]), 0.0)    # the columns differ from cell to cell
        self.assertGreater(np.ptp(f["c_c[6]"]), 0.0)
        s = printed(run, "S")[0]
        np.testing.assert_array_equal(s[:3], s[3:])
        np.testing.assert_allclose(s[:3], [f["c_c[1]"].sum(), f["c_c[4]"].sum(), f["c_c[9]"].sum()],
                                   rtol=1e-12, atol=1e-12)

    def check_t1_births(self, model):
        d = dim_of(model)
        sphere = model == "sphere"
        # The vertex model: a dying cell leaves only by moving its corners
        # (it shrinks until a T2 takes it), which a still tissue does not:
        # there, births alone.
        vertex = model.startswith("vertex_polygon")
        cols = " ".join("c_l[%d]" % k for k in range(1, 8 if d == 2 and not sphere else 10))
        steps = 6
        die = "" if vertex else "fix die all cell/death rate 2.0 seed 1733\n"
        script = model_script(model) + f"""compute t all vertex/tissue
compute l all vertex/local
fix div all cell/divide rate 4.0 seed 4821 separation 0.05
{die}timestep 0.01
thermo_style custom step atoms c_t[3] f_div[2] {"" if vertex else "f_die[2]"}
thermo 1
dump a all custom 1 ids.dump id
dump f all local 1 junctions.dump {cols}
dump_modify f format float %.17g
run {steps}
"""
        run = self.run_lmp(script)
        ids = [f["id"] for f in run.dump("ids.dump")]
        frames = local_rows(run, "junctions.dump")
        self.assertEqual(len(frames), steps + 1)
        self.assertEqual(len(ids), steps + 1)
        counts = self.thermo_column(run.stdout, "c_t[3]")
        births = self.thermo_column(run.stdout, "f_div[2]")
        deaths = [] if vertex else self.thermo_column(run.stdout, "f_die[2]")
        self.assertEqual(len(counts), steps + 1)
        pairs = [neighbour_pairs(rows, d, sphere) for rows in frames]
        expected, gained = [0], 0
        for k in range(1, steps + 1):
            clean, all_new = exchanges(pairs[k - 1], pairs[k], ids[k - 1], ids[k])
            expected.append(clean)
            gained += all_new
        self.assertEqual(counts, expected)
        self.assertEqual(sum(counts), 0)    # nothing moves: no exchange
        self.assertGreater(births[-1], 0)
        if vertex:
            return
        self.assertGreater(deaths[-1], 0)
        self.assertGreater(gained, 0)    # the deaths' neighbours met: not exchanges

    @staticmethod
    def thermo_column(stdout, name):
        header, values = None, []
        for line in stdout.splitlines():
            w = line.split()
            if w and w[0] == "Step":
                header = w
                continue
            if header and len(w) == len(header) and w[0].isdigit():
                values.append(float(w[header.index(name)]))
            elif header and not (w and w[0].isdigit()):
                header = None
        return values
