# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools segmented: a LAMMPS data file of a vertex tissue (pair_style
vertex/polygon) from the label image of a segmented, periodic patch of cells
(tessera_tools.segmented)."""

import numpy as np

from . import segmented
from .voronoi import polygon_area


def read_labels(path):
    """An integer label image: .npy, or text (whitespace or comma separated)."""
    if path.endswith(".npy"):
        lab = np.load(path)
    else:
        with open(path) as f:
            text = f.read().replace(",", " ")
        lab = np.array([[float(v) for v in line.split()] for line in text.splitlines()
                        if line.strip() and not line.lstrip().startswith("#")])
    if lab.ndim != 2:
        raise ValueError(f"{path}: a label image is a 2d array, got {lab.ndim} dimensions")
    if not np.all(np.isfinite(lab)) or not np.all(lab == np.round(lab)):
        raise ValueError(f"{path}: labels must be integers")
    return lab.astype(np.int64)


def cmd_segmented(args):
    lab = read_labels(args.labels)
    if args.origin == "upper":    # row 0 at the top, as images are stored
        lab = np.flipud(lab)
    if args.boundary_label is not None:
        lab = segmented.fill_boundaries(lab, args.boundary_label)
    if not args.pixel > 0:
        raise ValueError(f"--pixel must be > 0, got {args.pixel}")
    lab, joined = segmented.join_pinches(lab)
    t = segmented.tissue_from_labels(lab, args.pixel)
    segmented.write_data(t, args.output, cell_type=args.cell_type, vertex_type=args.vertex_type,
                         ntypes=max(args.types, args.cell_type, args.vertex_type),
                         width=args.maxsides, atom_style=args.atom_style)
    areas = [polygon_area(t.polygon(c)) for c in t.rings]
    print(f"{args.output}: {len(t.rings)} cells, {len(t.vertices)} vertices, box "
          f"{t.box[0]:.6g} x {t.box[1]:.6g}, mean cell area {np.mean(areas):.6g} "
          f"(rings in section vring, width {args.maxsides}); {joined} pixel(s) given to a "
          "diagonal neighbour's label to join it through sides")


def add_commands(sub):
    p = sub.add_parser(
        "segmented", help="a vertex tissue (data file) from a segmented image's labels",
        description="Write a LAMMPS data file for pair_style vertex/polygon from the label image of a "
                    "segmented, periodic patch of a confluent tissue: one integer label per pixel, each "
                    "cell one connected label without holes.  The junctions (pixel corners where three "
                    "or more labels meet) become vertex atoms, each cell a ring of them, counter-"
                    "clockwise, in section 'vring' (read it with 'fix vring all property/atom i2_vring "
                    "W' before 'read_data FILE fix vring NULL vring').  Cell atoms (IDs 1..N, in label "
                    "order) sit at their polygons' centroids.")
    p.add_argument("labels", help="the label image: .npy, or a text file of integers (one row of "
                                  "pixels per line)")
    p.add_argument("-o", "--output", required=True, help="the data file to write")
    p.add_argument("--pixel", type=float, default=1.0, help="the side of a pixel in length units "
                                                             "(default 1)")
    p.add_argument("--origin", choices=("upper", "lower"), default="upper",
                   help="where row 0 of the array is: the top of the image (upper, as image files "
                        "store it; default) or the bottom (lower)")
    p.add_argument("--boundary-label", type=int, default=None, metavar="L",
                   help="pixels of label L are boundaries between cells (watershed lines): each "
                        "takes a neighbouring cell's label first")
    p.add_argument("--maxsides", type=int, default=16, metavar="W",
                   help="the rings' width, the W of fix vring (default 16)")
    p.add_argument("--atom-style", choices=("atomic", "dipole"), default="atomic")
    p.add_argument("--cell-type", type=int, default=1)
    p.add_argument("--vertex-type", type=int, default=2)
    p.add_argument("--types", type=int, default=2, help="atom types in the file (default 2)")
    p.set_defaults(func=cmd_segmented)
