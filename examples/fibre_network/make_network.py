#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Writes the LAMMPS data file of examples/fibre_network: a periodic square
box holding a random network of straight fibres (bead-spring chains, atom
type 2) and cells (atom type 1) scattered in the free space between them.

* Fibres: NF straight fibres of length LF, centres uniform in the box,
  directions evenly spread over 180 degrees (so the network starts
  isotropic: the nematic order of its segments is close to 0) and shuffled.
  Each fibre is a chain of beads BEAD apart, joined by bonds of type 1 (rest
  length BEAD) and, along the chain, angles of type 1 (the bending
  stiffness).  Where two fibres cross, their two nearest beads are joined by
  a crosslink, a bond of type 2 (rest length 0 in the input script), except
  where the crossing closes a loop of crossing fibres around the periodic
  box (no consistent image flags exist for it).
* Cells: NC atoms of type 1 at random places at least CLEAR from every bead
  and 1.0 from each other, with a random unit polarity (the dipole).

Atom style ``hybrid dipole angle``: each Atoms line is
``id type x y z q mux muy muz molecule ix iy iz`` (molecule = the fibre's
number, 0 for cells; image flags that keep every fibre and every crosslink
contiguous).  Cells come first (ids 1..NC), then the fibres one after
the other, NB beads each: the ends of fibre f are beads NC + f NB + 1 and
NC + (f + 1) NB, which is how the input script finds them.

    make_network.py [-o fibres.data] [--seed 7] [--box 24] [--fibres 30] [--cells 48]
"""

import argparse
import math

import numpy as np


def crossing(c1, u1, c2, u2, length, box):
    """Arc-length positions (s1, s2) in [0, length] where fibre 2 (nearest
    periodic image of its centre) crosses fibre 1, or None."""
    d = c2 - c1
    d -= box * np.round(d / box)
    det = u1[0] * (-u2[1]) - u1[1] * (-u2[0])
    if abs(det) < 1e-9:
        return None
    # c1 + t1 u1 = c1 + d + t2 u2, t measured from the centres
    t1 = (d[0] * (-u2[1]) - d[1] * (-u2[0])) / det
    t2 = (u1[0] * d[1] - u1[1] * d[0]) / det
    h = 0.5 * length
    if abs(t1) > h or abs(t2) > h:
        return None
    return t1 + h, t2 + h


def build(seed=7, box=24.0, nfibres=30, length=8.0, bead=0.5, ncells=48, clear=1.1, mindist=1.0):
    rng = np.random.default_rng(seed)
    nb = int(round(length / bead)) + 1
    angles = (np.arange(nfibres) + rng.uniform(0, 1, nfibres)) * math.pi / nfibres
    rng.shuffle(angles)
    centres = rng.uniform(0, box, (nfibres, 2))
    dirs = np.column_stack([np.cos(angles), np.sin(angles)])
    beads = []      # (x, y, fibre)
    bonds = []      # (type, i, j), 0-based bead indices
    triples = []
    for f in range(nfibres):
        first = f * nb
        for k in range(1, nb):
            bonds.append((1, first + k - 1, first + k))
            if k > 1:
                triples.append((first + k - 2, first + k - 1, first + k))
    # Crossings, then image shifts of whole fibres (breadth first over the
    # crossings) so that crosslinked fibres are contiguous in unwrapped
    # coordinates; a crossing that closes a loop around the periodic box
    # cannot be made so and is left without a crosslink (LAMMPS would warn of
    # inconsistent image flags).
    cross = {}
    for f in range(nfibres):
        for g in range(f + 1, nfibres):
            s = crossing(centres[f], dirs[f], centres[g], dirs[g], length, box)
            if s is not None:
                cross.setdefault(f, []).append((g, s[0], s[1]))
                cross.setdefault(g, []).append((f, s[1], s[0]))
    placed = {}
    for root in range(nfibres):
        if root in placed:
            continue
        placed[root] = centres[root].copy()
        queue = [root]
        while queue:
            f = queue.pop(0)
            for g, _, _ in cross.get(f, []):
                if g not in placed:
                    d = centres[g] - placed[f]
                    placed[g] = placed[f] + d - box * np.round(d / box)
                    queue.append(g)
    links = set()
    skipped = 0
    for f, lst in cross.items():
        for g, sf, sg in lst:
            if g < f:
                continue
            d = placed[g] - placed[f]
            if np.any(np.abs(d - box * np.round(d / box) - d) > 1e-9):
                skipped += 1
                continue
            i = f * nb + int(round(sf / bead))
            j = g * nb + int(round(sg / bead))
            links.add((min(i, j), max(i, j)))
    bonds += [(2, i, j) for i, j in sorted(links)]
    for f in range(nfibres):
        for k in range(nb):
            beads.append(tuple(placed[f] + (k * bead - 0.5 * length) * dirs[f]) + (f + 1,))
    bxy = np.array([(b[0], b[1]) for b in beads])
    cells = []
    tries = 0
    while len(cells) < ncells:
        tries += 1
        if tries > 100000:
            raise SystemExit("make_network.py: no room for %d cells (placed %d); "
                             "use fewer cells or fibres" % (ncells, len(cells)))
        p = rng.uniform(0, box, 2)
        d = bxy - p
        d -= box * np.round(d / box)
        if np.min(np.hypot(d[:, 0], d[:, 1])) < clear:
            continue
        if cells:
            d = np.array(cells) - p
            d -= box * np.round(d / box)
            if np.min(np.hypot(d[:, 0], d[:, 1])) < mindist:
                continue
        cells.append(p)
    phi = rng.uniform(0, 2 * math.pi, ncells)
    return dict(box=box, nb=nb, bead=bead, cells=np.array(cells), phi=phi, beads=beads,
                bonds=bonds, angles=triples, nfibres=nfibres, links=len(links), skipped=skipped)


def write(net, path):
    cells, beads = net["cells"], net["beads"]
    nc = len(cells)
    with open(path, "w") as f:
        f.write("# examples/fibre_network: %d cells, %d fibres of %d beads, %d crosslinks "
                "(make_network.py)\n\n" % (nc, net["nfibres"], net["nb"], net["links"]))
        f.write("%d atoms\n2 atom types\n%d bonds\n2 bond types\n%d angles\n1 angle types\n\n"
                % (nc + len(beads), len(net["bonds"]), len(net["angles"])))
        f.write("0 %.1f xlo xhi\n0 %.1f ylo yhi\n-0.5 0.5 zlo zhi\n\n" % (net["box"], net["box"]))
        f.write("Masses\n\n1 1.0\n2 1.0\n\n")
        f.write("Atoms # hybrid\n\n")
        for i, (p, a) in enumerate(zip(cells, net["phi"])):
            f.write("%d 1 %.10f %.10f 0.0 0.0 %.10f %.10f 0.0 0 0 0 0\n"
                    % (i + 1, p[0], p[1], math.cos(a), math.sin(a)))
        box = net["box"]
        for i, (x, y, fib) in enumerate(beads):
            ix, iy = math.floor(x / box), math.floor(y / box)
            f.write("%d 2 %.10f %.10f 0.0 0.0 0.0 0.0 0.0 %d %d %d 0\n"
                    % (nc + i + 1, x - ix * box, y - iy * box, fib, ix, iy))
        f.write("\nBonds\n\n")
        for n, (t, i, j) in enumerate(net["bonds"]):
            f.write("%d %d %d %d\n" % (n + 1, t, nc + i + 1, nc + j + 1))
        f.write("\nAngles\n\n")
        for n, (i, j, k) in enumerate(net["angles"]):
            f.write("%d 1 %d %d %d\n" % (n + 1, nc + i + 1, nc + j + 1, nc + k + 1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--output", default="fibres.data")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--box", type=float, default=24.0)
    ap.add_argument("--fibres", type=int, default=30)
    ap.add_argument("--length", type=float, default=8.0)
    ap.add_argument("--cells", type=int, default=48)
    args = ap.parse_args()
    net = build(seed=args.seed, box=args.box, nfibres=args.fibres, length=args.length,
                ncells=args.cells)
    write(net, args.output)
    print("wrote %s: %d cells, %d beads, %d bonds (%d crosslinks; %d crossings closing a loop "
          "around the box left unlinked), %d angles"
          % (args.output, len(net["cells"]), len(net["beads"]), len(net["bonds"]),
             net["links"], net["skipped"], len(net["angles"])))


if __name__ == "__main__":
    main()
