"""The README's Python example: import a measurement, invert it, plot S and K.

    .venv/bin/python python/example_sk_plot.py docs/images/python_sk.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import rouge

m = rouge.read_measurement("data/measurements/blush_01_petal.csv").to_working_grid()
S, K = rouge.R_to_SK_KubelkaMunk(m.R_inf, m.R, m.R_g, m.thickness_mm, wavelengths=m.wavelengths)

fig, ax = plt.subplots(figsize=(7, 3.6))
ax.plot(m.wavelengths, S, label="S, scattering")
ax.plot(m.wavelengths, K, label="K, absorption")
ax.set(xlabel="wavelength (nm)", ylabel="mm⁻¹", yscale="log", title=f"{m.name}, {m.thickness_mm} mm layer")
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "sk.png", dpi=110)
