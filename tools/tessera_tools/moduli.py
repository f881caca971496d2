# SPDX-License-Identifier: GPL-2.0-or-later
"""Linear elastic moduli and vibrational spectrum of an energy-minimised tissue.

The exact Hessian H = d2E/dr dr of the vertex-model energy and the affine
strain terms come from the ``tessera-hessian`` executable (built with the
core: ``build/core/tessera-hessian``); this module runs it on a periodic
configuration and does the linear algebra with numpy/scipy:

* Born term ``d2E/dgamma^2`` at fixed reduced coordinates and
  ``Xi = d2E/dr dgamma`` for simple shear x += gamma y (LAMMPS's xy tilt) and
  for dilation r += eps r;
* relaxed second derivatives ``Born - Xi^T H^+ Xi`` (the non-affine
  relaxation removes the part of the response that moving the cells can
  undo; H^+ is the pseudo-inverse, which ignores the two translations);
* shear modulus ``G = (d2E/dgamma^2)_relaxed / V`` (the slope of -pxy
  against the tilt strain xy/ly after minimisation), bulk modulus
  ``B = V d2E/dV^2 = ((d2E/deps^2)_relaxed / V + 2 P) / 4`` with the
  pressure ``P = -dE/dV = (Wxx + Wyy) / (2 V)`` (the slope of -press against
  ln V after minimisation), Young's modulus ``E = 4 B G / (B + G)`` and
  Poisson's ratio ``nu = (B - G) / (B + G)`` (2D isotropic elasticity);
* the spectrum: eigenvalues of H (squared angular frequencies of the normal
  modes at unit mass).  Two zero modes are the translations; more zero modes
  mean floppy motions, and negative eigenvalues mean the configuration is not
  a minimum (e.g. the hexagonal lattice above p0 = sqrt(8 sqrt 3) = 3.7224).

The configuration must be an energy minimum (forces ~ 0) for G and B to be
the moduli; ``fnorm`` (the 2-norm of all forces, as LAMMPS's thermo keyword)
and ``max_force`` are reported so callers can check.  At a multifold
vertex the energy is not twice differentiable and tessera-hessian refuses.
"""

import os
import shutil
import subprocess

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def hessian_places():
    """Where :func:`find_hessian_exe` looks, in order, as (description, path or None)."""
    places = [("$TESSERA_HESSIAN", os.environ.get("TESSERA_HESSIAN") or None)]
    if os.environ.get("TESSERA_BUILD"):
        places.append(("$TESSERA_BUILD/core", os.path.join(os.environ["TESSERA_BUILD"], "core", "tessera-hessian")))
    places.append(("the repository's build", os.path.join(ROOT, "build", "core", "tessera-hessian")))
    places.append(("PATH", shutil.which("tessera-hessian")))
    return places


def find_hessian_exe(explicit=None):
    """The tessera-hessian executable: ``explicit`` (--exe), else $TESSERA_HESSIAN, else where
    scripts/build puts it (build/core/tessera-hessian of this repository, or $TESSERA_BUILD/core),
    else the first on PATH.  A path that is given (explicit or $TESSERA_HESSIAN) but is not an
    executable file is an error, not a reason to look elsewhere."""
    if explicit:
        if not (os.path.isfile(explicit) and os.access(explicit, os.X_OK)):
            raise FileNotFoundError(f"--exe {explicit}: no executable file there; give the path of "
                                    "tessera-hessian (scripts/build puts it in build/core/)")
        return os.path.abspath(explicit)
    env = os.environ.get("TESSERA_HESSIAN")
    if env and not (os.path.isfile(env) and os.access(env, os.X_OK)):
        raise FileNotFoundError(f"TESSERA_HESSIAN={env}: no executable file there; unset it or point it "
                                "at tessera-hessian (scripts/build puts it in build/core/)")
    places = hessian_places()
    for _, path in places:
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return os.path.abspath(path)
    looked = "; ".join(f"{what}" + (f" ({path})" if path else " (not set)" if what.startswith("$") else
                                     " (none)") for what, path in places)
    raise FileNotFoundError("tessera-hessian not found. Looked in: " + looked +
                            ". Build it (scripts/build, which puts it in build/core/), put it on PATH, "
                            "set TESSERA_HESSIAN=/path/to/tessera-hessian, or pass --exe PATH")


class Model:
    """Energy parameters per type (0-based): K, A0, Gamma lists and the Lambda matrix.

    E = sum_i K/2 (A_i - A0)^2 + Gamma/2 P_i^2 + tension term, as pair_coeff's
    ``K A0 Gamma Lambda`` form; ``tension`` is "edge" (default) or "cell".
    """

    def __init__(self, K, A0, Gamma, Lambda, tension="edge"):
        self.K = [float(v) for v in np.atleast_1d(K)]
        self.A0 = [float(v) for v in np.atleast_1d(A0)]
        self.Gamma = [float(v) for v in np.atleast_1d(Gamma)]
        n = len(self.K)
        self.Lambda = np.array(Lambda, dtype=float).reshape(n, n) if np.ndim(Lambda) else np.full((n, n), float(Lambda))
        if tension not in ("edge", "cell"):
            raise ValueError(f"tension must be 'edge' or 'cell', got {tension!r}")
        self.tension = tension

    @classmethod
    def quadratic(cls, KA, A0, KP, P0, tension="edge"):
        """E = sum KA (A - A0)^2 + KP (P - P0)^2 (pair_coeff ... quadratic KA A0 KP P0)."""
        w = 0.5 if tension == "edge" else 1.0
        return cls(2 * KA, A0, 2 * KP, -(2 * KP) * P0 / w, tension)


class HessianResult:
    """Output of tessera-hessian: energy, virial, forces, Born terms, Xi, H (scipy CSR)."""

    def __init__(self, text):
        import scipy.sparse

        lines = text.split("\n")
        head = {}
        i = 0
        while not lines[i].startswith("force"):
            key, *vals = lines[i].split()
            head[key] = [float(v) for v in vals]
            i += 1
        self.n = int(head["n"][0])
        self.area = head["area"][0]
        self.energy = head["energy"][0]
        self.virial = np.array(head["virial"])
        self.born_shear = head["born_shear"][0]
        self.born_dilation = head["born_dilation"][0]
        vec = {}
        for name in ("force", "xi_shear", "xi_dilation"):
            if lines[i].strip() != name:
                raise ValueError(f"tessera-hessian output: expected '{name}', got {lines[i]!r}")
            vec[name] = np.loadtxt(lines[i + 1:i + 1 + self.n]).reshape(-1)
            i += 1 + self.n
        self.force, self.xi_shear, self.xi_dilation = vec["force"], vec["xi_shear"], vec["xi_dilation"]
        key, nnz = lines[i].split()
        if key != "hessian":
            raise ValueError(f"tessera-hessian output: expected 'hessian NNZ', got {lines[i]!r}")
        nnz = int(nnz)
        trip = np.loadtxt(lines[i + 1:i + 1 + nnz]).reshape(-1, 3)
        m = 2 * self.n
        self.H = scipy.sparse.csr_matrix((trip[:, 2], (trip[:, 0].astype(int), trip[:, 1].astype(int))),
                                         shape=(m, m))


# Per-cell parameters of pair vertex/voronoi (fix property/atom names, as dump columns) and
# tessera-hessian's names for them.
CELL_COLUMNS = {"d_area0": "area0", "d_ka": "ka", "d_kp": "kp", "d_perim0": "perim0"}


def run_hessian(box, xy, model, types=None, exe=None, cells=None):
    """Run tessera-hessian on points xy (N x 2) in box (tessera_tools.dump.Box or (xlo, xhi, ylo, yhi, xy)).

    types: 1-based types per point (default all 1).  cells: optional per-cell
    parameters {"area0"|"ka"|"kp"|"perim0": N values} (LAMMPS's d_area0, d_ka,
    d_kp, d_perim0, quadratic-form values); each replaces the type's value for
    every cell, as in pair vertex/voronoi.  Raises RuntimeError with
    tessera-hessian's message on failure (e.g. a multifold vertex).
    """
    if hasattr(box, "xlo"):
        b = (box.xlo, box.xhi, box.ylo, box.yhi, box.xy)
    else:
        b = tuple(float(v) for v in box)
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    n = len(xy)
    types = np.ones(n, dtype=int) if types is None else np.asarray(types, dtype=int)
    nt = len(model.K)
    cells = {k: np.asarray(v, dtype=float).reshape(-1) for k, v in (cells or {}).items()}
    for k, v in cells.items():
        if k not in CELL_COLUMNS.values():
            raise ValueError(f"per-cell parameter {k!r}: expected one of {', '.join(CELL_COLUMNS.values())}")
        if len(v) != n:
            raise ValueError(f"per-cell parameter {k!r} has {len(v)} values for {n} points")
    names = list(cells)
    out = [" ".join(repr(float(v)) for v in b) + f" {n} {nt} {model.tension}"
           + (" cells " + " ".join(names) if names else "")]
    out += [f"{model.K[t]!r} {model.A0[t]!r} {model.Gamma[t]!r}" for t in range(nt)]
    out += [" ".join(repr(float(v)) for v in row) for row in model.Lambda]
    extra = np.column_stack([cells[k] for k in names]).tolist() if names else [[]] * n
    out += [f"{x!r} {y!r} {t}" + "".join(f" {float(v)!r}" for v in e)
            for (x, y), t, e in zip(xy.tolist(), types.tolist(), extra)]
    proc = subprocess.run([find_hessian_exe(exe)], input="\n".join(out) + "\n", capture_output=True,
                          text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(proc.stderr.strip() or f"tessera-hessian failed with status {proc.returncode}")
    return HessianResult(proc.stdout)


def _spectrum_solve(H, vectors, dense_limit):
    """Eigenvalues of H (dense path only) and x^T H^+ x for each vector."""
    m = H.shape[0]
    if m <= dense_limit:
        lam, phi = np.linalg.eigh(H.toarray())
        tol = 1e-9 * max(1.0, np.abs(lam).max())
        keep = np.abs(lam) > tol
        quad = [float(np.sum((phi[:, keep].T @ v) ** 2 / lam[keep])) for v in vectors]
        return lam, quad
    # Large: pin point 0 (removes the translations) and solve sparse.
    import scipy.sparse.linalg

    solve = scipy.sparse.linalg.factorized(H[2:, 2:].tocsc())  # one LU for all vectors
    return None, [float(v[2:] @ solve(v[2:])) for v in vectors]


def moduli(res, dense_limit=4000):
    """G, B, E, nu and the diagnostics of a HessianResult, as a dict.

    dense_limit: up to this many degrees of freedom (2N) H is diagonalised
    densely (and the spectrum returned as 'eigenvalues'); above it the
    non-affine terms come from a sparse solve and there is no spectrum.
    """
    V = res.area
    lam, (na_s, na_d) = _spectrum_solve(res.H, [res.xi_shear, res.xi_dilation], dense_limit)
    pressure = (res.virial[0] + res.virial[1]) / (2 * V)
    G = (res.born_shear - na_s) / V
    B = ((res.born_dilation - na_d) / V + 2 * pressure) / 4
    out = dict(G=G, B=B, E=4 * B * G / (B + G), nu=(B - G) / (B + G), pressure=pressure,
               shear_stress=-res.virial[2] / V, G_affine=res.born_shear / V,
               B_affine=(res.born_dilation / V + 2 * pressure) / 4, energy=res.energy, area=V, n=res.n,
               max_force=float(np.abs(res.force).max()), fnorm=float(np.linalg.norm(res.force)),
               force_vector=res.force)
    if lam is not None:
        tol = 1e-9 * max(1.0, np.abs(lam).max())
        out.update(eigenvalues=lam, zero_modes=int(np.sum(np.abs(lam) <= tol)),
                   negative_modes=int(np.sum(lam < -tol)), lowest_nonzero=float(lam[np.abs(lam) > tol][0]))
    return out


def frame_cells(frame):
    """The per-cell parameters a dump frame carries (columns d_area0, d_ka, d_kp, d_perim0),
    as run_hessian's ``cells``."""
    return {name: frame[col] for col, name in CELL_COLUMNS.items() if col in frame}


def frame_moduli(frame, model, exe=None, dense_limit=4000, use_types=True):
    """moduli() of a tessera_tools.dump.Frame (positions x y, optional type column, and the
    per-cell parameters d_area0, d_ka, d_kp, d_perim0 where the dump has them).  Every atom of
    the frame is a cell: read the dump with ``cell_types`` to leave particles out.
    ``use_types`` False gives every cell the model's first type, whatever its type column.

    The result also holds 'cells' (the per-cell columns used) and, when the dump has the
    forces fx fy, 'dump_fnorm' (their 2-norm) and 'force_mismatch' (the largest difference
    between them and the forces of the energy used here): a state whose own forces vanish
    while this energy's do not was run with another energy (other coefficients, or per-cell
    parameters the dump does not carry)."""
    types = frame["type"] if use_types and "type" in frame else None
    cells = frame_cells(frame)
    out = moduli(run_hessian(frame.box, frame.positions(), model, types, exe, cells), dense_limit)
    out["cells"] = [col for col in CELL_COLUMNS if col in frame]
    if "fx" in frame and "fy" in frame:
        f = np.column_stack([frame["fx"], frame["fy"]]).astype(float)
        out["dump_fnorm"] = float(np.linalg.norm(f))
        out["force_mismatch"] = float(np.abs(f.reshape(-1) - out["force_vector"]).max())
    return out


def fit_quasistatic(path):
    """Slopes of the quasistatic strain steps written by examples/moduli/in.moduli.

    Lines ``shear gamma pxy press pe fnorm`` and ``dilation eps pxy press pe
    fnorm``: G = -d pxy / d gamma, B = -d press / d ln V = -(1/2) d press / d eps.
    Returns a dict with G, G_err, B, B_err (standard errors of least-squares
    slopes, from the scatter of the points about the line), and the raw arrays.
    """
    rows = {"shear": [], "dilation": []}
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] in rows:
                rows[w[0]].append([float(v) for v in w[1:]])
    out = {}
    for kind, y_col, factor, name in (("shear", 1, 1.0, "G"), ("dilation", 2, 0.5, "B")):
        a = np.array(rows[kind])
        if len(a) < 3:
            raise ValueError(f"{path}: need at least 3 '{kind}' lines for a slope with an error, got {len(a)}")
        x, y = a[:, 0], -a[:, y_col]
        (slope, _), cov = np.polyfit(x, y, 1, cov="unscaled")
        resid = y - np.polyval(np.polyfit(x, y, 1), x)
        s2 = resid @ resid / max(1, len(x) - 2)
        out[name] = factor * slope
        out[name + "_err"] = factor * float(np.sqrt(cov[0, 0] * s2))
        out[kind] = a
        if a.shape[1] >= 5:
            out[kind + "_fnorm"] = float(np.max(a[:, 4]))
    out["fnorm"] = max(out.get("shear_fnorm", 0.0), out.get("dilation_fnorm", 0.0))
    out.update(young_poisson(out["G"], out["B"], out["G_err"], out["B_err"]))
    return out


def young_poisson(G, B, G_err=0.0, B_err=0.0):
    """E = 4 B G / (B + G) and nu = (B - G) / (B + G) (2D isotropic elasticity) with their
    errors propagated linearly from independent errors of G and B."""
    s = B + G
    E = 4 * B * G / s
    nu = (B - G) / s
    E_err = float(np.hypot(4 * B * B / s ** 2 * G_err, 4 * G * G / s ** 2 * B_err))
    nu_err = float(np.hypot(2 * B / s ** 2 * G_err, 2 * G / s ** 2 * B_err))
    return dict(E=E, E_err=E_err, nu=nu, nu_err=nu_err)


def seed_average(values):
    """Mean and standard error of the mean (sample standard deviation / sqrt(n)) of the
    values of independent states; the error is NaN for a single state."""
    v = np.asarray([x for x in values if x is not None and np.isfinite(x)], dtype=float)
    if len(v) == 0:
        return float("nan"), float("nan")
    if len(v) == 1:
        return float(v[0]), float("nan")
    return float(v.mean()), float(v.std(ddof=1) / np.sqrt(len(v)))
