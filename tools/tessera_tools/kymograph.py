# SPDX-License-Identifier: GPL-2.0-or-later
"""Kymographs: a per-cell quantity (any per-atom dump column, e.g. a species ``d_erk``) and the
cell density binned along the x or y axis of the box, frame by frame, and the wavelength and
period of a travelling pattern measured from them.

The bins are equal slices of the box along the axis (by fractional coordinate, so a box that
grows or is tilted keeps its N slices); a bin's value is the mean of the column over the cells
whose centres lie in it, and its density the number of those cells per unit area (the count over
the slice's area, box area / N; in a 3d box the area of the x-y plane).  An empty bin has no mean:
it is NaN in the arrays (masked in the picture, an empty field in the CSV) and density 0; for the
measurement it takes the value interpolated linearly between the nearest full bins (periodically).

:func:`measure_wave` takes the 2d Fourier transform of the kymograph (time x position, the mean
removed, under a Hann window in both directions) and reads the wavelength and the period off its
strongest peak, refined between frequency samples by a parabola through the logarithms of the
peak and its neighbours: a pattern at a whole number of wavelengths across the box and of periods
over the record is found exactly, others to a few hundredths of a frequency sample (the
resolution is one wavelength across the box and one period over the record).
"""

import numpy as np

from .dump import iter_dump

AXES = {"x": 0, "y": 1}


class Kymograph:
    """``steps``, ``times`` (T), bin ``edges`` (N+1) and ``centres`` (N) along the axis in the
    first frame's box, ``values`` and ``density`` (T, N), the ``column`` and ``axis``."""

    def __init__(self, column, axis, steps, times, edges, values, density, counts, time_known):
        self.column, self.axis = column, axis
        self.steps, self.times = np.asarray(steps), np.asarray(times, dtype=float)
        self.edges = np.asarray(edges, dtype=float)
        self.centres = 0.5 * (self.edges[1:] + self.edges[:-1])
        self.values, self.density, self.counts = values, density, counts
        self.time_known = time_known

    @property
    def length(self):
        return self.edges[-1] - self.edges[0]

    def write_csv(self, path):
        """One row per frame and bin: timestep,time,position,COLUMN,count,density."""
        with open(path, "w") as f:
            f.write(f"timestep,time,position,{self.column},count,density\n")
            for k in range(len(self.steps)):
                for b in range(len(self.centres)):
                    v = self.values[k, b]
                    f.write(f"{self.steps[k]},{self.times[k]:.10g},{self.centres[b]:.10g},"
                            f"{'' if np.isnan(v) else format(v, '.10g')},{self.counts[k, b]},"
                            f"{self.density[k, b]:.10g}\n")

    def write_npz(self, path):
        np.savez(path, steps=self.steps, times=self.times, edges=self.edges, centres=self.centres,
                 values=self.values, density=self.density, counts=self.counts,
                 column=np.array(self.column), axis=np.array(self.axis))


def kymograph(frames, column, axis="x", bins=40, dt=None):
    """The :class:`Kymograph` of ``column`` over ``frames`` (an iterable of dump frames or a
    dump path).  ``dt``: time per timestep (default: the dump's TIME item, else timesteps)."""
    if axis not in AXES:
        raise ValueError(f"axis must be x or y, not '{axis}'")
    if bins < 1:
        raise ValueError(f"bins must be at least 1, not {bins}")
    if isinstance(frames, str):
        frames = iter_dump(frames)
    a = AXES[axis]
    steps, times, values, density, counts = [], [], [], [], []
    edges, known = None, True
    for frame in frames:
        if column not in frame:
            raise KeyError(f"column '{column}' is not in the dump at timestep {frame.timestep} "
                           f"(columns: {' '.join(frame.names)})")
        c = np.asarray(frame[column])
        if c.dtype.kind not in "iuf":
            raise ValueError(f"column '{column}' is not numeric")
        box = frame.box
        s = box.to_fractional(frame.positions())[:, a]
        s = s - np.floor(s) if box.periodic[a] else s
        k = np.floor(s * bins).astype(int)
        inside = (k >= 0) & (k < bins)
        n = np.bincount(k[inside], minlength=bins)
        total = np.bincount(k[inside], weights=c[inside].astype(float), minlength=bins)
        with np.errstate(invalid="ignore", divide="ignore"):
            values.append(np.where(n > 0, total / np.maximum(n, 1), np.nan))
        counts.append(n)
        density.append(n / (box.area / bins))
        if edges is None:
            lo = (box.xlo, box.ylo)[a]
            edges = lo + np.linspace(0.0, 1.0, bins + 1) * (box.lx, box.ly)[a]
        steps.append(frame.timestep)
        if dt is not None:
            times.append(frame.timestep * dt)
        elif frame.time is not None:
            times.append(frame.time)
        else:
            times.append(float(frame.timestep))
            known = False
    if not steps:
        raise ValueError("no frames")
    return Kymograph(column, axis, steps, times, edges, np.array(values), np.array(density),
                     np.array(counts), known or dt is not None)


def _refine(m, i, size):
    """Offset of the peak of the windowed magnitudes ``m`` (1d, periodic) near index i: the
    vertex of the parabola through the logarithms of the peak and its two neighbours (exact for
    a Gaussian peak, within a few hundredths of a sample for the Hann window's)."""
    a, b, c = (np.log(max(m[j % size], 1e-300)) for j in (i - 1, i, i + 1))
    den = a - 2 * b + c
    return 0.0 if den >= 0 else float(np.clip(0.5 * (a - c) / den, -0.5, 0.5))


def _hann(n):
    """The periodic Hann window: a sinusoid at a whole number of cycles keeps a peak symmetric
    about its sample (the two neighbours at half its height), so it is found exactly."""
    return 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(n) / n)


def measure_wave(times, positions, field):
    """Wavelength, period and phase velocity of the strongest travelling or standing pattern
    of ``field`` (T, N) sampled at equally spaced ``times`` and bin ``positions``: a dict with
    ``wavelength``, ``period`` (inf for a pattern that does not move), ``velocity`` (+ along the
    axis), ``power`` (the peak's fraction of the fluctuation power: near 1 for one clean wave)."""
    f = np.array(field, dtype=float)
    times = np.asarray(times, dtype=float)
    positions = np.asarray(positions, dtype=float)
    T, N = f.shape
    if T < 2 or N < 2:
        raise ValueError(f"a wave needs at least 2 frames and 2 bins (have {T} frames, {N} bins)")
    step = np.diff(times)
    if np.any(step <= 0) or np.ptp(step) > 1e-6 * abs(step.mean()):
        raise ValueError("the frames are not equally spaced in time; select equally spaced frames "
                         "(e.g. --frames ::K) to measure a period")
    dx = (positions[-1] - positions[0]) / (N - 1)
    if np.isnan(f).any():     # empty bins: interpolated linearly from the nearest full ones, around the box
        seen = ~np.isnan(f)
        if not seen.any(axis=1).all():
            raise ValueError("a frame has no cell in any bin")
        cells = np.arange(N)
        for k in np.nonzero(~seen.all(axis=1))[0]:
            f[k, ~seen[k]] = np.interp(cells[~seen[k]], cells[seen[k]], f[k, seen[k]], period=N)
    f = f - f.mean()
    power = np.abs(np.fft.fft2(f)) ** 2
    total = power.sum()
    if total <= 1e-24 * max(1.0, float(np.sum(np.array(field, dtype=float)[~np.isnan(field)] ** 2))):
        raise ValueError("the field is uniform: there is no pattern to measure")
    amp = np.abs(np.fft.fft2(f * _hann(T)[:, None] * _hann(N)[None, :]))
    half = amp.copy()
    half[:, N // 2 + 1:] = 0.0         # a real field: (w, k) and (-w, -k) carry the same power
    half[:, 0] = 0.0                   # no spatial pattern along the axis: not a wave
    it, ix = np.unravel_index(np.argmax(half), half.shape)
    if half[it, ix] <= 1e-12 * amp.max():
        raise ValueError("the field varies in time only, not along the axis: no wavelength")
    fx = (ix + _refine(amp[it, :], ix, N)) / (N * dx)
    signed_t = it if it <= T // 2 else it - T
    ft = (signed_t + _refine(amp[:, ix], it, T)) / (T * step.mean())
    # numpy's transform pairs exp(+i(k x - w t)) with (fx < 0, ft > 0): at fx > 0, ft = -w/(2 pi)
    period = np.inf if signed_t == 0 else 1.0 / abs(ft)
    peak = power[it, ix] * (2 if 0 < ix < N / 2 else 1)
    return {"wavelength": 1.0 / fx, "period": period, "velocity": -ft / fx if signed_t else 0.0,
            "power": float(peak / total)}
