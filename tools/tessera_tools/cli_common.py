# SPDX-License-Identifier: GPL-2.0-or-later
"""Helpers the tessera-tools commands share: frame slices, matplotlib without a display, progress bars."""

import argparse
import itertools


def _matplotlib():
    import matplotlib

    matplotlib.use("Agg")


def _slice(text):
    """'start:stop:step' (Python slice syntax, any part may be empty) or 'all'."""
    if text in ("all", ":"):
        return slice(None)
    parts = text.split(":")
    if len(parts) == 1:
        k = int(parts[0])
        return slice(k, k + 1 if k != -1 else None)
    if len(parts) > 3:
        raise argparse.ArgumentTypeError(f"bad frame slice '{text}'")
    try:
        return slice(*[int(p) if p.strip() else None for p in parts])
    except ValueError:
        raise argparse.ArgumentTypeError(f"bad frame slice '{text}'") from None


def _select_frames(path, sl, cell_types=None):
    from .dump import iter_dump, read_dump

    if all(v is None or v >= 0 for v in (sl.start, sl.stop)) and (sl.step is None or sl.step > 0):
        frames = list(itertools.islice(iter_dump(path, cell_types), sl.start, sl.stop, sl.step))
    else:
        frames = read_dump(path, cell_types=cell_types)[sl]
    if not frames:
        raise SystemExit(f"tessera-tools: no frames of {path} selected by the slice")
    return frames


def _progress(enabled=True):
    """tqdm progress bars on stderr when tqdm is installed (Debian: python3-tqdm) and wanted."""
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return lambda it, desc=None, **kw: tqdm(it, desc=desc, unit="frame", leave=False, **kw)
