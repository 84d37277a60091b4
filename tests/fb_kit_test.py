"""What the engine kit's tests share (test_planar_kit.py and each binding's):
the peak keys of summary.json, a relative difference, a run's models, and
the in-line slider-crank written as a planar case: crank 50 mm at 30
degrees, rod 120 mm, the slider on the x axis (prismatic slider-ground),
driven at 3000 rpm."""
import json, os

PEAK_KEYS = ("omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2")

CRANK_PIN_MM = (43.30127018922193, 25.0)  # the crank's pin at 30 degrees
SLIDER_X_MM = CRANK_PIN_MM[0] + (120.0 ** 2 - 25.0 ** 2) ** 0.5


def rel(p, q):
    """|p - q| / |q|"""
    return abs(p - q) / max(abs(q), 1e-300)


def models(folder):
    """summary.json's models of the run written to folder, by name"""
    with open(os.path.join(folder, "summary.json")) as f:
        return {m["name"]: m for m in json.load(f)["models"]}


def slider_text(models):
    """the case file's text with [run] models = models"""
    c, sx = CRANK_PIN_MM, SLIDER_X_MM
    return """[case]
name = planar_slider
[linkage]
type = planar
[joint.ground-crank]
bodies = ground, crank
at_mm = 0, 0
[joint.crank-rod]
bodies = crank, rod
at_mm = %.12f, %.12f
[joint.rod-slider]
bodies = rod, slider
at_mm = %.12f, 0
[joint.slider-ground]
bodies = slider, ground
at_mm = %.12f, 0
kind = prismatic
axis_deg = 0
[body.slider]
mass_kg = 0.14
inertia_kg_mm2 = 20
[drive]
joint = ground-crank
speed_rpm = 3000
[pin]
fit = 10H7/g6
length_mm = 13
[run]
models = %s
""" % (c[0], c[1], sx, sx, models)
