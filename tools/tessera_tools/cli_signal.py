# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools plot kymograph, plot field: a per-cell species (any per-atom column, such as the
d_NAME columns of fix property/atom) along a line against time, and on the cells of one frame."""

import numpy as np

from .cli_common import _matplotlib, _slice


def cmd_plot_kymograph(args):
    from .cli_common import _select_frames
    from .kymograph import kymograph, measure_wave

    if not (args.output or args.csv or args.npz or args.measure):
        raise SystemExit("tessera-tools plot kymograph: nothing to do: give -o PICTURE, --csv FILE, --npz FILE "
                         "or --measure")
    frames = _select_frames(args.dump, args.frames or slice(None), args.cell_types)
    kymo = kymograph(frames, args.column, args.axis, args.bins, args.dt)
    unit = "time" if kymo.time_known else "timesteps"
    empty = int(np.sum(kymo.counts == 0))
    print(f"kymograph of {args.column} along {args.axis}: {len(kymo.steps)} frames x {args.bins} bins of width "
          f"{kymo.length / args.bins:.6g}" + (f"; {empty} empty (frame, bin) pairs" if empty else ""))
    if args.output:
        from .plots import plot_kymograph

        plot_kymograph(kymo, args.output, dpi=args.dpi, vector=args.vector, title=args.title)
        print(f"wrote {args.output}")
    if args.csv:
        kymo.write_csv(args.csv)
        print(f"wrote {args.csv}")
    if args.npz:
        kymo.write_npz(args.npz)
        print(f"wrote {args.npz}")
    if args.measure:
        for name, field in ((args.column, kymo.values), ("density", kymo.density)):
            try:
                w = measure_wave(kymo.times, kymo.centres, field)
            except ValueError as err:
                print(f"{name}: no wave measured ({err})")
                continue
            moving = np.isfinite(w["period"])
            period = f"{w['period']:.6g} {unit}" if moving else "inf (the pattern does not move)"
            print(f"{name}: wavelength {w['wavelength']:.6g}, period {period}, phase velocity "
                  f"{w['velocity']:.6g} along +{args.axis}, peak {100 * w['power']:.1f}% of the fluctuation power")


def cmd_plot_field(args):
    _matplotlib()
    from .plots import plot_field

    if args.local:
        from .junctions import junction_columns, junction_tessellation, paired_frames

        pairs = paired_frames(args.dump, args.local, cell_types=args.cell_types)
        frame, local = pairs[args.frame]
        if len(junction_columns(local)) != 7:
            raise SystemExit(f"tessera-tools plot field: {args.local} holds 3d or sphere cells; draw those with "
                             "'tessera-tools vtk' (species are cell data there)")
        tess = junction_tessellation(frame, local)
    else:
        from .dump import read_frame
        from .render import tessellate_frame

        frame = read_frame(args.dump, index=args.frame, cell_types=args.cell_types)
        if not args.radius and not (frame.box.periodic[0] and frame.box.periodic[1]):
            raise SystemExit(f"tessera-tools plot field: {args.dump}: the box is not periodic in x and y; give "
                             "the cells with --local (a dump local of compute vertex/local) or --radius R")
        tess = tessellate_frame(frame, args.radius)
    values, _, _ = plot_field(frame, tess, args.column, args.output, view=args.view, cmap=args.cmap,
                              vmin=args.vmin, vmax=args.vmax, dpi=args.dpi, vector=args.vector, title=args.title)
    print(f"wrote {args.output}: timestep {frame.timestep}, {len(tess)} cells, {args.column} from "
          f"{np.nanmin(values):.6g} to {np.nanmax(values):.6g} (mean {np.nanmean(values):.6g})")


def add_plot_commands(psub, common, add_cell_types):
    """Add 'kymograph' and 'field' to the subparsers of tessera-tools plot; ``common`` adds the
    picture options, ``add_cell_types`` the --cell-types option."""
    pk = psub.add_parser("kymograph", help="a species and the cell density along x or y against time",
                         description="Bin the cells of each frame along the x (or y) axis of the box: the mean "
                                     "of a per-atom column (a species d_NAME, or any column) and the number of "
                                     "cells per unit area, as two panels against time; optionally the arrays "
                                     "(--csv, --npz) and the wavelength and period of the strongest travelling "
                                     "pattern, from the peak of the kymographs' 2d Fourier transform (--measure).")
    pk.add_argument("dump", help="dump custom file with id, x y and the column")
    pk.add_argument("-c", "--column", required=True, help="per-atom column, e.g. d_erk")
    pk.add_argument("--axis", choices=("x", "y"), default="x", help="the line: along x (default) or y")
    pk.add_argument("--bins", type=int, default=40, help="number of equal bins across the box (default 40)")
    pk.add_argument("--frames", type=_slice, help="slice of frames, e.g. '100::2' (default: all)")
    pk.add_argument("--dt", type=float, help="timestep size (time = timestep x dt; else the dump's TIME)")
    pk.add_argument("--csv", metavar="FILE", help="write the arrays: timestep,time,position,COLUMN,count,density")
    pk.add_argument("--npz", metavar="FILE", help="write the arrays as a numpy .npz")
    pk.add_argument("--measure", action="store_true", help="print the wavelength and period of the patterns")
    add_cell_types(pk, "; only the cells are binned")
    common(pk, required=False)
    pk.set_defaults(func=cmd_plot_kymograph)

    pf = psub.add_parser("field", help="a species' field on the cells of one frame, with a colour bar",
                         description="Each cell (Voronoi polygon) of one frame coloured by a per-atom column.")
    pf.add_argument("dump", help="dump custom file with id, x y and the column")
    pf.add_argument("-c", "--column", required=True, help="per-atom column, e.g. d_delta")
    pf.add_argument("--frame", type=int, default=-1, help="frame index (default -1: the last)")
    pf.add_argument("--local", metavar="DUMP", help="dump local of compute vertex/local: LAMMPS's own polygons")
    pf.add_argument("--radius", type=float, help="finite Voronoi cells of this radius (open tissues)")
    pf.add_argument("--view", choices=("box", "cells"), default="box")
    pf.add_argument("--cmap", help="matplotlib colour map (default viridis)")
    pf.add_argument("--vmin", type=float)
    pf.add_argument("--vmax", type=float)
    add_cell_types(pf)
    common(pf)
    pf.set_defaults(func=cmd_plot_field)
