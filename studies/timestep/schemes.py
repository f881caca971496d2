# SPDX-License-Identifier: GPL-2.0-or-later
"""Forward Euler (fix brownian) against stochastic Heun (fix brownian/heun), for
studies/timestep/run: strong errors of a deterministic active tissue against a
fine reference, the cost at equal accuracy, the weak error of a stationary
average with rotational noise, the thesis's fluid at its timestep, and the
largest timestep of the grooves example without collisions."""

import math
import os
import re

import numpy as np

from studylib import fit_power, md_table, parse_log, plt
from tessera_tools.dump import read_frame

SCHEMES = {"euler": "brownian", "heun": "brownian/heun"}
LABEL = {"euler": "forward Euler (fix brownian)", "heun": "Heun (fix brownian/heun)"}
COLOR = {"euler": "tab:blue", "heun": "tab:red"}

ACTIVE = """# active tissue, deterministic: {scheme} at dt = {dt!r} (studies/timestep/run)
dimension       2
units           lj
atom_style      dipole
boundary        p p p
lattice         hex 1.0
region          box block 0 10 0 5 -0.5 0.5
create_box      1 box
create_atoms    1 box
mass            1 1.0
displace_atoms  all random 0.15 0.15 0 4821 units box
pair_style      vertex/voronoi 3.0
pair_coeff      * * 1.0 1.0 0.1 -0.5
fix             p all polarity 0.3 1.0 neighbor 1.0 groove 1.0 30 velocity 1.0
fix             b all {style} 1.0 1 gamma_t 1.0 rng none
timestep        {dt!r}
thermo          0
run             {n}
write_dump      all custom final.dump id xu yu mux muy modify format float %.17g sort id
"""

WEAK = """# free polarities with groove alignment and rotational noise: {scheme} at dt = {dt!r}
dimension       2
units           lj
atom_style      dipole
boundary        p p p
lattice         sq 1.0
region          box block 0 {side} 0 {side} -0.5 0.5
create_box      1 box
create_atoms    1 box
mass            1 1.0
pair_style      zero 0.5
pair_coeff      * *
fix             p all polarity 0.0 1.0 groove {JG} 0.0 noise {Dr} {seed}
fix             b all {style} 1.0 1 gamma_t 1.0 rng none
timestep        {dt!r}
thermo_style    custom step f_p[2]
thermo_modify   format float %.12g
thermo          {every}
run             {n}
"""

FLUID = """# the thesis's fluid (5.1.2): {scheme} at dt = {dt!r}, energy at every step
dimension       2
units           lj
atom_style      dipole
boundary        p p p
lattice         hex 1.0
region          box block 0 10 0 5 -0.5 0.5
create_box      1 box
create_atoms    1 box
mass            1 1.0
region          site sphere 5.3728 3.7224 0 0.3 units box
group           one region site
displace_atoms  one move 0.1 0.05 0 units box
pair_style      vertex/voronoi 6.0
pair_coeff      * * 1.0 1.0 0.1 -1.5
fix             move all {style} 1.0 12908410 gamma_t 1.0 rng none
thermo_style    custom step pe
thermo_modify   norm yes format float %.15g
thermo          1
run             {n}
"""



def order_text(order, points):
    """A fitted order and its number of points, or why there is none (a slope needs 2 points)."""
    if np.isfinite(order):
        return f"{order:.2f} ({points} points)"
    return f"not measured ({points} point{'s' if points != 1 else ''} above the noise; a slope needs 2)"

def grooves_script(root, style, dt, seed):
    with open(os.path.join(root, "examples", "grooves", "in.grooves")) as f:
        script = f.read()
    script = script.replace("fix             move all brownian ", f"fix             move all {style} ")
    script = re.sub(r"(?m)^dump.*\n", "", script)
    assert style in script
    return script


def completed(log_path):
    """The run reached its end (a failed run's log has no final wall time)."""
    if not os.path.exists(log_path):
        return False
    with open(log_path, errors="replace") as f:
        return "Total wall time" in f.read()


def loop_time(log_path):
    with open(log_path) as f:
        m = re.search(r"Loop time of ([0-9.eE+-]+) on", f.read())
    return float(m.group(1)) if m else float("nan")


def add_args(parser):
    parser.add_argument("--groove-seeds", type=int, default=200,
                        help="seeds 1..N of the grooves collision sweep (default 200)")


class Schemes:
    def __init__(self, study, root):
        self.study = study
        self.root = root
        q = study.quick
        self.t_active = 0.2 if q else 1.0
        self.k_active = range(0, 3) if q else range(0, 7)
        self.k_ref = 4 if q else 9
        self.dt0_active = 0.1
        self.weak_dts = [0.2, 0.1] if q else [0.4, 0.2, 0.1, 0.05]
        self.weak = dict(side=16 if q else 128, JG=2.0, Dr=0.5, t_eq=1.0 if q else 3.0,
                         t_avg=2.0 if q else 120.0)
        self.fluid_dts = [0.1, 0.0125] if q else [0.1 / 2 ** k for k in range(0, 7)]
        self.t_fluid = 1.0 if q else 10.0
        self.groove_dts = [0.0125, 0.05] if q else [0.0125, 0.025, 0.05, 0.1]
        self.groove_seeds = range(1, 3) if q else range(1, study.args.groove_seeds + 1)
        self.t_grooves = 1.0 if q else 5.0

    def jobs(self):
        jobs, self.meta = [], []
        out = os.path.join(self.study.out, "schemes")
        for scheme, style in SCHEMES.items():
            for k in self.k_active:
                dt = self.dt0_active / 2 ** k
                d = os.path.join(out, f"active_{scheme}_k{k}")
                jobs.append((d, ACTIVE.format(scheme=scheme, style=style, dt=dt,
                                              n=int(round(self.t_active / dt)))))
                self.meta.append(("active", scheme, dt, d))
        dt = self.dt0_active / 2 ** self.k_ref
        d = os.path.join(out, "active_reference")
        jobs.append((d, ACTIVE.format(scheme="heun", style=SCHEMES["heun"], dt=dt,
                                      n=int(round(self.t_active / dt)))))
        self.meta.append(("active_ref", "heun", dt, d))
        w = self.weak
        for scheme, style in SCHEMES.items():
            for dt in self.weak_dts:
                d = os.path.join(out, f"weak_{scheme}_dt{dt:g}")
                n = int(round((w["t_eq"] + w["t_avg"]) / dt))
                jobs.append((d, WEAK.format(scheme=scheme, style=style, dt=dt, n=n, seed=8123,
                                            every=max(1, int(round(0.1 / dt))), **w)))
                self.meta.append(("weak", scheme, dt, d))
            for dt in self.fluid_dts:
                d = os.path.join(out, f"fluid_{scheme}_dt{dt:g}")
                jobs.append((d, FLUID.format(scheme=scheme, style=style, dt=dt,
                                             n=int(round(self.t_fluid / dt)))))
                self.meta.append(("fluid", scheme, dt, d))
            for dt in self.groove_dts:
                for seed in self.groove_seeds:
                    d = os.path.join(out, f"grooves_{scheme}_dt{dt:g}_s{seed}")
                    script = grooves_script(self.root, style, dt, seed)
                    jobs.append((d, script, {"seed": seed, "dt": dt, "tend": self.t_grooves}))
                    self.meta.append(("grooves", scheme, dt, d, seed))
        return jobs

    # ------------------------------------------------------------ analysis
    def analyse(self):
        res = {"active": {s: [] for s in SCHEMES}, "weak": {s: [] for s in SCHEMES},
               "fluid": {s: [] for s in SCHEMES}, "grooves": {}}
        ref = None
        for m in self.meta:
            if m[0] == "active_ref":
                ref = read_frame(os.path.join(m[3], "final.dump"))
        self.ref_dt = self.dt0_active / 2 ** self.k_ref
        for m in self.meta:
            kind, scheme, dt, d = m[:4]
            log = os.path.join(d, "log.lammps")
            ok = completed(log)
            if kind == "active" and ok:
                fr = read_frame(os.path.join(d, "final.dump"))
                dr = fr.unwrapped() - ref.unwrapped()
                dn = np.column_stack([fr["mux"] - ref["mux"], fr["muy"] - ref["muy"]])
                res["active"][scheme].append(dict(
                    dt=dt, err_r=float(np.sqrt(np.mean(np.sum(dr ** 2, axis=1)))),
                    err_n=float(np.sqrt(np.mean(np.sum(dn ** 2, axis=1)))),
                    cpu=loop_time(log) / self.t_active,
                    evals=(2.0 if scheme == "heun" else 1.0) / dt))
            elif kind == "weak" and ok:
                run = parse_log(log).runs[-1]
                t = run["Step"] * dt
                y = run["f_p[2]"][t >= self.weak["t_eq"]]
                nb = 10 if len(y) >= 20 else max(1, len(y) // 2)
                blocks = np.array_split(y, nb)
                means = np.array([b.mean() for b in blocks])
                res["weak"][scheme].append(dict(dt=dt, mean=float(y.mean()),
                                                sem=float(means.std(ddof=1) / math.sqrt(nb)) if nb > 1 else float("nan")))
            elif kind == "fluid" and ok:
                run = parse_log(log).runs[-1]
                e = run["PotEng"]
                de = np.diff(e)
                res["fluid"][scheme].append(dict(
                    dt=dt, t=run["Step"] * dt, E=e, E_final=float(e[-1]),
                    rises=int((de > 1e-12).sum()), steps=len(de),
                    max_rise=float(de.max()) if len(de) else 0.0,
                    first_rise=float(run["Step"][1:][de > 1e-12][0] * dt) if (de > 1e-12).any() else float("nan"),
                    cpu=loop_time(log) / self.t_fluid))
            elif kind == "grooves":
                key = (scheme, dt)
                res["grooves"].setdefault(key, []).append((m[4], ok))
        for s in SCHEMES:
            for kind in ("active", "weak", "fluid"):
                res[kind][s].sort(key=lambda r: -r["dt"])
        kappa = self.weak["JG"] / (4 * 1.0 * self.weak["Dr"])
        self.weak_exact = bessel_ratio(kappa)
        self.res = res
        return res

    # ------------------------------------------------------------- figure
    def figure(self):
        res = self.res
        fig, axes = plt.subplots(2, 2, figsize=(12, 9))
        ax = axes[0, 0]
        self.fits = {}
        for s in SCHEMES:
            rs = res["active"][s]
            dts = np.array([r["dt"] for r in rs])
            for key, marker, what in (("err_r", "o", "positions"), ("err_n", "^", "polarities")):
                y = np.array([r[key] for r in rs])
                p, _ = fit_power(dts[-4:], y[-4:])
                self.fits[(s, key)] = p
                ax.loglog(dts, y, marker + "-", color=COLOR[s], mfc="none" if key == "err_n" else None,
                          label=f"{s}, {what}: slope {p:.2f}")
        ax.set_xlabel(r"timestep $\Delta t$")
        ax.set_ylabel(f"RMS error at t = {self.t_active:g} vs Heun at dt = {self.ref_dt:.2g}")
        ax.set_title("deterministic active tissue (100 cells)")
        ax.legend(fontsize=8)
        ax = axes[0, 1]
        for s in SCHEMES:
            rs = res["active"][s]
            ax.loglog([r["evals"] for r in rs], [r["err_r"] for r in rs], "o-", color=COLOR[s],
                      label=LABEL[s] + ", positions")
        ax.set_xlabel("force computations per unit simulated time (Heun: 2 per step)")
        ax.set_ylabel("RMS position error")
        ax.set_title("cost at equal accuracy")
        ax.legend(fontsize=8)
        ax = axes[1, 0]
        for s in SCHEMES:
            rs = res["weak"][s]
            dts = np.array([r["dt"] for r in rs])
            err = np.array([abs(r["mean"] - self.weak_exact) for r in rs])
            sem = np.array([r["sem"] for r in rs])
            ax.errorbar(dts, err, yerr=2 * sem, fmt="o-", color=COLOR[s], capsize=3,
                        label=LABEL[s])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"timestep $\Delta t$")
        ax.set_ylabel(r"$|\langle\cos 2\theta\rangle - I_1(\kappa)/I_0(\kappa)|$ (2 s.e. bars)")
        ax.set_title("weak error: groove alignment + rotational noise")
        ax.legend(fontsize=8)
        ax = axes[1, 1]
        for s in SCHEMES:
            for r in res["fluid"][s]:
                if abs(r["dt"] - 0.0125) < 1e-9:
                    ax.plot(r["t"], r["E"], color=COLOR[s], lw=1, label=f"{s}, dt = 0.0125")
            fine = res["fluid"][s][-1] if res["fluid"][s] else None
            if fine is not None and abs(fine["dt"] - 0.0125) > 1e-9:
                ax.plot(fine["t"], fine["E"], color=COLOR[s], lw=1, ls=":", label=f"{s}, dt = {fine['dt']:.2g}")
        ax.set_xlabel("time t")
        ax.set_ylabel("E/N")
        ax.set_title("the thesis's fluid (p0 = 7.5)")
        ax.legend(fontsize=8)
        fig.tight_layout()
        return self.study.savefig(fig, "schemes.png")

    # ------------------------------------------------------------- report
    def equal_accuracy(self, target):
        """CPU per unit simulated time for RMS position error `target`, from each
        scheme's power law err = C dt^p (4 finest timesteps) and its CPU time per
        step (median over its runs): cost = (CPU per step) / dt(target)."""
        out = {}
        for s in SCHEMES:
            rs = self.res["active"][s]
            dts = np.array([r["dt"] for r in rs])
            err = np.array([r["err_r"] for r in rs])
            p, c = fit_power(dts[-4:], err[-4:])
            per_step = float(np.median([r["cpu"] * r["dt"] for r in rs[-3:]]))    # longest runs
            dt = (target / c) ** (1.0 / p) if p > 0 else float("nan")
            evals = (2.0 if s == "heun" else 1.0) / dt
            out[s] = dict(cost=per_step / dt, dt=dt, per_step=per_step, evals=evals)
        return out

    def report(self):
        res = self.res
        rows = []
        for s in SCHEMES:
            for r in res["active"][s]:
                rows.append([s, f"{r['dt']:.5g}", f"{r['err_r']:.2e}", f"{r['err_n']:.2e}",
                             f"{r['evals']:.0f}", f"{r['cpu']:.3f}"])
        t_active = md_table(["scheme", "dt", "RMS position error", "RMS polarity error",
                             "force evaluations / unit time", "CPU s / unit time"], rows)
        eq = {t: self.equal_accuracy(t) for t in (1e-3, 1e-4, 1e-5)}
        eq_rows = [[f"{t:.0e}", f"{v['euler']['dt']:.2g}", f"{v['euler']['evals']:.3g}",
                    f"{v['heun']['dt']:.2g}", f"{v['heun']['evals']:.3g}",
                    f"{v['euler']['evals'] / v['heun']['evals']:.1f}"] for t, v in eq.items()]
        t_eq = md_table(["RMS position error", "Euler dt", "Euler force computations / unit time",
                         "Heun dt", "Heun force computations / unit time", "Euler / Heun"], eq_rows)
        any_eq = next(iter(eq.values()))
        step_ratio = any_eq["heun"]["per_step"] / any_eq["euler"]["per_step"]
        wrows = []
        for s in SCHEMES:
            for r in res["weak"][s]:
                wrows.append([s, f"{r['dt']:g}", f"{r['mean']:.5f}", f"{r['mean'] - self.weak_exact:+.5f}",
                              f"{r['sem']:.1e}"])
        t_weak = md_table(["scheme", "dt", "<cos 2 theta>", "minus exact", "standard error"], wrows)
        wfit = {}
        for s in SCHEMES:
            rs = res["weak"][s]
            dts = np.array([r["dt"] for r in rs])
            err = np.array([abs(r["mean"] - self.weak_exact) for r in rs])
            sig = np.array([r["sem"] for r in rs])
            keep = err > 3 * sig
            wfit[s] = (fit_power(dts[keep], err[keep])[0], int(keep.sum()))
        local = {}
        for sc in SCHEMES:
            rs = res["weak"][sc]
            parts = []
            for a, b in zip(rs, rs[1:]):
                ea, eb = abs(a["mean"] - self.weak_exact), abs(b["mean"] - self.weak_exact)
                slope = math.log2(ea / eb) if eb > 0 and ea > 0 else float("nan")
                txt = f"{slope:.2f}"
                parts.append(txt if eb > 3 * b["sem"] else f"({txt})")
            local[sc] = ", ".join(parts)
        ratios = [abs(e["mean"] - self.weak_exact) / abs(h["mean"] - self.weak_exact)
                  for e, h in zip(res["weak"]["euler"], res["weak"]["heun"])
                  if abs(h["mean"] - self.weak_exact) > 3 * h["sem"]]
        ratio_lo, ratio_hi = (min(ratios), max(ratios)) if ratios else (float("nan"), float("nan"))
        frows = []
        for s in SCHEMES:
            for r in res["fluid"][s]:
                frows.append([s, f"{r['dt']:.5g}", f"{r['E_final']:.5f}",
                              "yes" if r["E_final"] < r["E"][0] - 0.01 else "no",
                              f"{r['rises']} / {r['steps']}",
                              f"{r['max_rise']:.1e}", (f"{r['first_rise']:.3g}" if np.isfinite(r["first_rise"]) else "never"), f"{r['cpu']:.3f}"])
        t_fluid = md_table(["scheme", "dt", f"E/N at t = {self.t_fluid:g}", "un-jammed", "steps where E rises",
                            "largest rise of E/N", "first rise at t", "CPU s / unit time"], frows)
        grows, largest, rate = [], {}, {}
        for s in SCHEMES:
            for dt in self.groove_dts:
                runs = res["grooves"].get((s, dt), [])
                bad = [seed for seed, ok in runs if not ok]
                grows.append([s, f"{dt:g}", f"{len(runs) - len(bad)} / {len(runs)}",
                              ", ".join(map(str, bad[:12])) + (" ..." if len(bad) > 12 else "") or "-"])
                rate[(s, dt)] = (len(bad), len(runs))
            for dt in self.groove_dts:    # ascending: up to the first dt with a failure
                nbad, nrun = rate[(s, dt)]
                if nrun == 0 or nbad > 0:
                    break
                largest[s] = dt
        t_grooves = md_table(["scheme", "dt", "runs completed", "seeds that failed"], grows)
        fl = {s: {round(r["dt"], 9): r for r in res["fluid"][s]} for s in SCHEMES}
        th = {s: fl[s].get(0.0125) for s in SCHEMES}
        mono = {s: [r["dt"] for r in res["fluid"][s] if r["rises"] == 0] for s in SCHEMES}
        f = self.fits
        dt_big = self.groove_dts[-1]
        nbad = {sc: sum(1 for _, ok in res["grooves"].get((sc, dt_big), []) if not ok) for sc in SCHEMES}
        groove_note = ""
        if nbad["heun"] > nbad["euler"]:
            groove_note = (f" At dt = {dt_big:g} Heun fails more often than Euler ({nbad['heun']} against "
                           f"{nbad['euler']} seeds): its predictor alone moves a cell by f_a dt / gamma_t = "
                           f"{10 * dt_big:g} cell size(s), and the forces at such a predicted state (two "
                           "centres nearly on top of each other) wreck the corrector. A higher order does "
                           "not enlarge the stable timestep of an explicit scheme.")
        fewer = [dt for dt in self.groove_dts if rate[("heun", dt)][0] < rate[("euler", dt)][0]]
        if not groove_note and len(fewer) == len(self.groove_dts):
            first = {sc: min((dt for dt in self.groove_dts if rate[(sc, dt)][0]), default=None) for sc in SCHEMES}
            groove_note = (" At every timestep of the list Heun lost fewer seeds than Euler; neither is free of "
                           "collisions (first failed seed: " + ", ".join(
                               f"{sc.capitalize()} at dt = {first[sc]:g}" if first[sc] else f"{sc.capitalize()} none"
                               for sc in SCHEMES) + "): a higher order makes them rarer but an explicit step "
                           "still overshoots when two centres nearly collide.")
        if th["heun"] and th["heun"]["rises"] == 0:
            mono_verdict = ": with Heun it is monotonic"
        elif th["heun"]:
            mono_verdict = ": the energy is not monotonic with Heun either"
        else:
            mono_verdict = ""
        seeds = list(self.groove_seeds)
        text = f"""
## Forward Euler against Heun (fix brownian/heun)

![schemes](figures/schemes.png)

**Deterministic active tissue** (100 cells of a jittered solid, p0 = 2.5, `fix polarity 0.3
1.0 neighbor 1.0 groove 1.0 30 velocity 1.0`, no noise, t = {self.t_active:g}), each run
against one reference run of Heun at dt = {self.ref_dt:.3g}; RMS over cells of the
position and polarity-vector differences. Slopes fitted to the 4 finest timesteps:
Euler {f[('euler', 'err_r')]:.2f} (positions) and {f[('euler', 'err_n')]:.2f} (polarities), Heun
{f[('heun', 'err_r')]:.2f} and {f[('heun', 'err_n')]:.2f}: first and second order, for the
coupled positions and polarities alike (the test `test_fix_brownian_heun` checks the same with
Richardson ratios: Heun >= 1.8, Euler 0.8-1.2).

{t_active}
Cost at equal accuracy: the timestep each scheme needs for a given RMS position error
(from its fitted power law), and from it the force computations per unit simulated time
(Heun: two per step), a cost that does not depend on the machine. The force computation
(tessellation and forces) is most of a step's CPU time; measured on the shared 2-core
machine (so roughly), a Heun step cost {step_ratio:.2f} Euler steps in these runs (median
CPU time per step of each scheme's 3 longest runs; the last column of the table above).

{t_eq}
**Weak error with noise.** {self.weak['side'] ** 2} free polarities (no translation), groove
alignment J_G = {self.weak['JG']:g}, rotational diffusion D_r = {self.weak['Dr']:g}, gamma_R = 1:
d theta = -(J_G / 2) sin 2 theta dt + sqrt(2 D_r) dW, whose stationary density is
proportional to exp(kappa cos 2 theta), kappa = J_G / (4 D_r) = {self.weak['JG'] / (4 * self.weak['Dr']):g}, so
<cos 2 theta> = I_1(kappa)/I_0(kappa) = **{self.weak_exact:.5f}**. Time average over
t = {self.weak['t_eq']:g} to {self.weak['t_eq'] + self.weak['t_avg']:g} (fix polarity's
global value 2), standard error from 10 blocks.

{t_weak}
Fitted weak order (over the timesteps whose error exceeds 3 standard errors): Euler
{order_text(*wfit['euler'])}, Heun {order_text(*wfit['heun'])}.
Local slopes log2(err(2 dt)/err(dt)), from the coarsest pair down: Euler {local['euler']}; Heun
{local['heun']} (a slope whose finer point is within 3 standard errors of 0 is in brackets).
Euler's bias is first order from the start; Heun's is {ratio_lo:.0f} to {ratio_hi:.0f} times smaller at
equal dt and steepens as dt falls (towards the weak order 2 of the theory), but at
these statistics the finest errors reach the noise before the asymptotic slope can be read
off.

**The thesis's fluid** (p0 = 7.5, one displaced cell, as above), energy at every step to
t = {self.t_fluid:g}:

{t_fluid}
At the thesis's dt = 0.0125, {th['euler']['rises'] if th['euler'] else '-'} (Euler) and
{th['heun']['rises'] if th['heun'] else '-'} (Heun) of the {th['euler']['steps'] if th['euler'] else '-'} steps raise the energy{mono_verdict}. Timesteps with a monotonic energy
up to t = {self.t_fluid:g}: Euler {', '.join(f'{d:.3g}' for d in mono['euler']) or 'none'}; Heun
{', '.join(f'{d:.3g}' for d in mono['heun']) or 'none'}; but a run that has not un-jammed
(E/N still within 0.01 of its start, the displaced cell relaxed back into the
hexagonal lattice) is a smooth relaxation whose energy falls trivially. Once the tissue
un-jams, the energy rises at a large fraction of the steps for every timestep here, with
either scheme, and the rises do not shrink with dt: junctions shrink to nearly zero length,
the forces near such nearly-fourfold vertices are large and change fast (the dynamics is
stiff there), and an explicit step, whatever its order, overshoots back and forth. A higher
order helps where the trajectory is smooth (the active tissue above, the solid), not at
these kinks; there only a much smaller step does, which `fix dt/reset` can choose
(`examples/heun`).

**Largest timestep without collisions**, `examples/grooves` (f_a = 10, J_S = J_G = 5,
t = {self.t_grooves:g}) with seeds {seeds[0]}-{seeds[-1]} for the initial polarities
({len(seeds) * len(self.groove_dts) * 2} runs; `--groove-seeds N` changes the range), at the
thesis's dt = 0.0125 and above (smaller timesteps only make collisions rarer). A run fails
when two centres come so close that the next step throws a cell so far that LAMMPS would lose
it (the pair style's step guard then stops the run, naming the atoms, their distance and the
step) or the pair style cannot build the cells. Builds without the guard let many of these runs go on
after such a step and counted them as completed.

{t_grooves}
Largest timestep of this list up to which every seed completed (at it and at every smaller
one): {'; '.join(f"{sc.capitalize()} {largest[sc]:g}" if sc in largest else f"{sc.capitalize()} none (a seed failed at dt = {self.groove_dts[0]:g})" for sc in SCHEMES)}. Failed runs per timestep:
{'; '.join(f"dt = {dt:g}: Euler {rate[('euler', dt)][0]}, Heun {rate[('heun', dt)][0]}" for dt in self.groove_dts)}
(of {len(seeds)} each). Collisions are rare events of chaotic trajectories, so a seed
that fails at one timestep may complete at a larger one.{groove_note}
"""
        return text


def bessel_ratio(kappa):
    """I_1(kappa) / I_0(kappa) by their power series."""
    i0 = i1 = 0.0
    term0, term1 = 1.0, kappa / 2
    for k in range(60):
        i0 += term0
        i1 += term1
        term0 *= (kappa / 2) ** 2 / ((k + 1) ** 2)
        term1 *= (kappa / 2) ** 2 / ((k + 1) * (k + 2))
    return i1 / i0
