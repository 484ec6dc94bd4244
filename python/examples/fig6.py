"""The paper's Fig. 6: the top velocity q' against t for models/ichinose1986.toml.

    pip install ./python matplotlib
    python3 python/examples/fig6.py [OUT.png]     # default: fig6.png
"""

import sys
from pathlib import Path

import flexrock

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("this example needs matplotlib: pip install matplotlib")

root = Path(__file__).resolve().parents[2]
model = flexrock.Model.from_file(root / "models" / "ichinose1986.toml")
result = flexrock.simulate(model)

fig, ax = plt.subplots(figsize=(8, 3.5))
ax.plot(result.t, result.qdot, lw=1)
for e in result.events:
    ax.axvline(e["t"], color="0.8", lw=0.5, zorder=0)
ax.set_xlabel("t (s)")
ax.set_ylabel("q' (m/s)")
ax.set_title(f"Ichinose (1986) Fig. 6: top velocity; {result.summary['n_uplift']} uplifts")
out = sys.argv[1] if len(sys.argv) > 1 else "fig6.png"
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
