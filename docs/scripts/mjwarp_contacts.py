"""Where MuJoCo Warp parts from MuJoCo C at 10 m (docs/mjwarp.md, issue 37): MuJoCo C steps the atlas's
fixed λ 2 block of height H (free rocking from 0.5α, 3·√H s, the `full` preset) and every 7th of its
states is handed to MuJoCo Warp's forward (`mujoco_warp.forward`, float32, on Warp's CPU device): does
Warp's collision find the contact C finds there? Counted over C's states where the block rests on its
pivot alone (one shallow contact pair, depth under 1e-5·H), and those of them within 0.05α of flat.

    python docs/scripts/mjwarp_contacts.py [H ...]      # default 0.1 1 10
"""
import sys

import mujoco
import numpy as np
import warp as wp
import mujoco_warp as mjw

from isorock.analytic.system import System
from isorock.mujoco_models import Settings
from isorock.mujoco_models.batch import prepare
from isorock.mujoco_models.mjwarp import _model, _warp

_warp()  # quiet
for height in [float(h) for h in sys.argv[1:]] or [0.1, 1.0, 10.0]:
    system = System.fixed(height=height, width=height / 2, mass=969387.7551020412 * (height / 10) ** 3)
    b = prepare(system, [None], Settings(phased=False), 3 * height ** 0.5, [0.5 * system.alpha], "C")
    model, data, lay = _model(b.model), b.starts[0], b.lay
    total = lost = near = near_lost = 0
    depths = []
    with wp.ScopedDevice("cpu"):
        m = mjw.put_model(model)
        for k in range(b.nstep):
            mujoco.mj_step(model, data)
            if k % 7:
                continue
            c = mujoco.MjData(model)
            c.qpos[:], c.qvel[:], c.qacc_warmstart[:] = data.qpos, data.qvel, data.qacc_warmstart
            mujoco.mj_forward(model, c)
            if not c.ncon or abs(c.contact.dist[:c.ncon]).min() >= 1e-5 * height:
                continue
            d = mjw.put_data(model, c)
            mjw.forward(m, d)
            found = int(d.nacon.numpy()[0]) > 0
            flat = abs(c.qpos[lay.thq]) < 0.05 * system.alpha
            total, lost = total + 1, lost + (not found)
            near, near_lost = near + flat, near_lost + (flat and not found)
            depths.append(-c.contact.dist[:c.ncon].min())
    print(f"H {height:g} m: Warp finds no contact in {lost} of C's {total} pivot states ({lost / total:.1%}), "
          f"{near_lost} of the {near} within 0.05α of flat; C's depth there, median {np.median(depths):.3g} m "
          f"({np.median(depths) / height:.2g}·H)", flush=True)
