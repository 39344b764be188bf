"""The non-linear isolators' closed-form errors and costs on the reference path, as quoted in
docs/isolators.md (tests/test_isolators.py asserts the same closed forms to 1e-9).

    python docs/scripts/isolator_closed_forms.py
"""
import math
import time
from pathlib import Path

import numpy as np

from isorock.analytic import load_motion
from isorock.analytic.system import BilinearIsolator, FrictionPendulum, System
from isorock.analytic.hybrid import simulate
B = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0); G = 9.81
fp = lambda R, mu: System.with_isolator(**B, isolator=FrictionPendulum(radius=R, friction_coefficient=mu))
R, u0 = 1.5, 0.05; w = math.sqrt(G / R)
tr = simulate(fp(R, 0.0), None, duration=6.0, u0=u0)
print("period: max|u − u0 cos ωt|/u0 =", np.max(np.abs(tr.u - u0*np.cos(w*tr.t)))/u0,
      " max |t_k − kπ/ω| =", max(abs(t - k*math.pi/w) for k, (t, _, _) in enumerate(tr.extras["isolator_events"], 1)))
mu, u0 = 0.005, 0.1
tr = simulate(fp(R, mu), None, duration=12.0, u0=u0)
errs = []; amp = u0
for k, (t, ph, u) in enumerate(tr.extras["isolator_events"], 1):
    amp -= 2*mu*R; errs.append(abs(u - (-1)**k*amp))
print("free decay: max peak error (m) =", max(errs), "events", len(tr.extras["isolator_events"]))
A, f = 0.3, 1.0
tr = simulate(fp(1.0, 0.05), load_motion(f"sine:amp={A},freq={f},cycles=1"), duration=1.5)
print("slip onset error (s) =", abs(tr.extras["isolator_events"][0][0] - math.asin(0.05/A)/(2*math.pi*f)))
k0, r, u_y, a = 3e5, 0.5, 0.005, 0.1
tr = simulate(System.with_isolator(**B, isolator=BilinearIsolator(k0, r, u_y)), None, duration=6.0, u0=a)
k_e, k_p = (1-r)*k0, r*k0; f_s = k_e*u_y
ev = tr.extras["isolator_events"]; u_p = a-u_y; u_c = k_e*u_p/k0
print("yield time error (s) =", abs(ev[0][0] - math.acos((u_p-u_y-u_c)/(a-u_c))/math.sqrt(k0/7600)))
x, tp, pe, le = a, 0.0, [], []
for k, (t, u) in enumerate([(t, u) for t, ph, u in ev if ph == 0], 1):
    c = 0.5*k_p*x*x - f_s*x + 2*f_s*u_y; n = (-f_s + math.sqrt(f_s*f_s + 2*k_p*c))/k_p
    if x + n <= 2*u_y: break
    pe.append(abs(u - (-1)**k*n))
    L = np.interp(t, tr.t, tr.energy.isolator_loss) - np.interp(tp, tr.t, tr.energy.isolator_loss)
    le.append(abs(L/(f_s*(x+n-2*u_y)) - 1)); x, tp = n, t
print("bearing: peaks", len(pe), "max peak error (m)", max(pe), "max loop-area rel error", max(le))
kobe = load_motion(str(Path(__file__).resolve().parents[2].parent / "shared" / "data" / "records" / "KOBE_NS"))
for name, s, m in (("FP R0.5 μ0.05 sine 0.6g 1.5Hz", fp(0.5, 0.05), "sine:amp=0.6,freq=1.5,cycles=2"),
                   ("FP R1 μ0.25 sine 0.9g 2Hz (pinned rocking)", fp(1.0, 0.25), "sine:amp=0.9,freq=2.0,cycles=3"),
                   ("FP R0.8 μ0.02 Kobe JMA", fp(0.8, 0.02), kobe),
                   ("FP R1 μ0.06 Kobe JMA", fp(1.0, 0.06), kobe),
                   ("bilinear 3e6 0.1 2mm c1000 sine 0.45g 2Hz", System.with_isolator(**B, isolator=BilinearIsolator(3e6, 0.1, 0.002, 1000.0)), "sine:amp=0.45,freq=2,cycles=3"),
                   ("bilinear 3e6 0.1 2mm c1000 Kobe JMA", System.with_isolator(**B, isolator=BilinearIsolator(3e6, 0.1, 0.002, 1000.0)), kobe)):
    t0 = time.perf_counter(); tr = simulate(s, m if not isinstance(m, str) else load_motion(m)); dt = time.perf_counter() - t0
    print(f"{name}: uplifts {tr.uplifts} impacts {tr.impact_count} θmax/α {tr.theta_max_over_alpha:.3f} u_max {tr.u_max:.4f} m, "
          f"overturned {tr.overturned}, slip events {len(tr.extras['isolator_events'])}, residual {tr.energy.relative_residual:.2e}, wall {dt:.1f} s")
