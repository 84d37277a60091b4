"""What the engine kit's Simbody test shares with fb_script: the peak keys
of summary.json, a relative difference, a run's models (the planar
slider-crank is fb_script.planar_slider_crank)."""

import fb_script

PEAK_KEYS = ("omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2")


def rel(p, q):
    """|p - q| / |q| (fb_script.rel)"""
    return fb_script.rel(p, q)


def models(folder):
    """summary.json's models of the run written to folder, by name (fb_script.models)"""
    return fb_script.models(folder)
