"""scripts/plot_capstan.py: each panel holds only the rows of its fixed value (issue 11: with
several phi from --phi-deg the 270 deg point was drawn in the 135 deg panel).
usage: python3 test_plot_capstan.py SOURCE_DIR"""
import sys

sys.path.insert(0, sys.argv[1] + "/scripts")
import plot_capstan  # noqa: E402

rows = []
for k, (mu, phi) in enumerate([(m, p) for m in (0.0, 0.3, 0.6) for p in (2.356194490, 4.712388980)]):
    rows.append({"case": f"c{k + 1}", "sweep": "c", "mu": str(mu), "phi": str(phi),
                 "T_ratio": "1", "exact": "1", "status": "full_slip"})
ps = plot_capstan.panels(rows)
assert len(ps) == 2, ps
for sweep, over_mu, fixed, sel in ps:
    assert over_mu and sweep == "c"
    assert len(sel) == 3 and all(abs(float(r["phi"]) - fixed) < 1e-12 for r in sel), (fixed, sel)
# the model's two sweeps: a over mu at one phi, b over phi at one mu
rows = [{"case": "a1", "sweep": "a", "mu": "0", "phi": "3.14"}, {"case": "a2", "sweep": "a", "mu": "0.3", "phi": "3.14"},
        {"case": "b1", "sweep": "b", "mu": "0.3", "phi": "1"}, {"case": "b2", "sweep": "b", "mu": "0.3", "phi": "2"}]
ps = plot_capstan.panels(rows)
assert [(p[0], p[1], len(p[3])) for p in ps] == [("a", True, 2), ("b", False, 2)], ps
print("ok")
