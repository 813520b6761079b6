"""Build a force model from plain options (tool kind, sizes in mm, angles in degrees where the name
says so) and evaluate it: the engine behind ``netshape forces``."""

from __future__ import annotations

import math

import numpy as np

from netshape._core import force as _f

_LINEAR_KEYS = ("Ktc", "Krc", "Kac", "Kte", "Kre", "Kae")


def parse_named_values(text: str, keys: tuple[str, ...]) -> dict[str, float]:
    """``"NAME=VALUE,…"`` with NAME one of ``keys`` (case-insensitive) → {lower-case name: finite float}.
    Empty items are skipped; ValueError names the bad item, key or value."""
    values: dict[str, float] = {}
    known = {k.lower(): k for k in keys}
    for item in text.split(","):
        if not item.strip():
            continue
        if "=" not in item:
            raise ValueError(f"coefficients item = {item.strip()!r}: expected NAME=VALUE")
        k, v = (s.strip() for s in item.split("=", 1))
        if k.lower() not in known:
            raise ValueError(f"coefficients key = {k!r}: must be one of {', '.join(keys)}")
        try:
            x = float(v)
        except ValueError:
            raise ValueError(f"coefficients {k} = {v!r}: not a number") from None
        if not math.isfinite(x):
            raise ValueError(f"coefficients {k} = {v!r}: must be finite")
        values[k.lower()] = x
    return values


def parse_coefficients(text: str) -> "_f.LinearEdgeCoefficients":
    """``"Ktc=…,Krc=…,Kac=…,Kte=…,Kre=…,Kae=…"`` (case-insensitive keys; missing keys are 0; at least
    one key) → LinearEdgeCoefficients. ValueError names the bad item."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"coefficients = {text!r}: expected Ktc=…,Krc=…,Kac=…,Kte=…,Kre=…,Kae=…")
    values = parse_named_values(text, _LINEAR_KEYS)
    if not values:
        raise ValueError(f"coefficients = {text!r}: no NAME=VALUE items")
    return _f.LinearEdgeCoefficients(**values)


def cutter_forces(
    *,
    tool: str = "flat",
    diameter: float,
    flutes: int,
    helix_deg: float,
    feed_per_tooth: float,
    ap: float,
    ae: float | None = None,
    mode: str = "slot",
    coefficients=None,
    coefficient_set: str | None = None,
    inclination_deg: float = 0.0,
    samples_per_revolution: int = 360,
    revolutions: float = 1.0,
    disk_height: float = 0.02,
    extension=None,
) -> tuple[np.ndarray, np.ndarray]:
    """Forces on the cutter over ``revolutions`` turns.

    Returns (angles (n,) [rad], forces (n, 3) [N]); the angle is the immersion φ of flute 1 at the
    tool tip. ``tool`` = "flat" (linear edge ``coefficients`` or a named linear set) or "ball"
    (a BallEndCoefficients or a named ball set, default ``kim_zas_ball12``; ``inclination_deg`` = ramp ξ).
    ``ae`` [mm] is measured from the wall to the tool's largest radius (diameter/2); in up and down
    milling a ball element of radius r(z) < diameter/2 meets that wall at its own angle (no cut where
    r(z) ≤ diameter/2 − ae). For ``mode="slot"`` ae is the diameter or None. ``extension``: a
    RunoutSizeEffect: cutter runout and chip-size effect (flat end mills); a ball end mill takes its
    runout (chip along the element normal) and refuses a chip exponent ≠ 1 (its size effect is
    Feng–Menq's m_T, m_R). See docs/force.md.
    """
    if tool not in ("flat", "ball"):
        raise ValueError(f"tool = {tool!r}: must be flat or ball")
    for name, v in (("diameter", diameter), ("helix_deg", helix_deg), ("feed_per_tooth", feed_per_tooth),
                    ("ap", ap), ("inclination_deg", inclination_deg), ("revolutions", revolutions)):
        if not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"{name} = {v!r}: must be a finite number")
    if diameter <= 0:
        raise ValueError(f"diameter = {diameter}: must be positive [mm]")
    if isinstance(flutes, bool) or not isinstance(flutes, int):
        raise ValueError(f"flutes = {flutes!r}: must be an integer")  # 1..64: checked by the C++ model
    if feed_per_tooth <= 0:
        raise ValueError(f"feed_per_tooth = {feed_per_tooth}: must be positive [mm]")
    if ap <= 0:
        raise ValueError(f"ap = {ap}: must be positive [mm]")
    if samples_per_revolution < 8:
        raise ValueError(f"samples_per_revolution = {samples_per_revolution}: must be at least 8")
    if revolutions < 1:
        raise ValueError(f"revolutions = {revolutions}: must be at least 1")
    radius = 0.5 * diameter
    mode_e = _f.milling_mode_from_string(mode)
    if mode_e != _f.MillingMode.slot:
        if ae is None or not math.isfinite(ae) or ae <= 0 or ae > diameter:
            raise ValueError(f"ae = {ae}: radial depth must be in (0, diameter] [mm] for {mode} milling")
    elif ae is not None and not (math.isfinite(ae) and abs(ae - diameter) <= 1e-9 * diameter):
        raise ValueError(f"ae = {ae}: a slot is cut by the whole tool, its radial depth is the diameter "
                         f"({diameter:g} mm); give ae = diameter or none")
    engagement = _f.AngularEngagement.from_mode(mode_e, radius, float(ae or 0.0))
    count = int(round(samples_per_revolution * revolutions))
    angles = _f.rotation_angles(count, float(revolutions))
    helix = math.radians(helix_deg)
    if tool == "flat":
        if coefficient_set is not None:
            k = _f.linear_edge_coefficient_set(coefficient_set).coefficients
        elif coefficients is None:
            raise ValueError("coefficients = None: give linear edge coefficients or a coefficient set")
        else:
            k = parse_coefficients(coefficients) if isinstance(coefficients, str) else coefficients
        if abs(inclination_deg) > 0:
            raise ValueError(f"inclination_deg = {inclination_deg}: ramp cuts are modelled for ball end mills only")
        model = _f.FlatEndModel(radius=radius, flutes=flutes, helix=helix, axial_depth=ap,
                                feed_per_tooth=feed_per_tooth, engagement=engagement, linear_edge=k,
                                disk_height=min(disk_height, ap))
        if extension is not None and not extension.none():
            return angles, _f.flat_end_forces_extended(model, extension, angles)
        return angles, _f.flat_end_forces(model, angles)
    ext = extension if extension is not None else _f.RunoutSizeEffect()
    if ext.chip_exponent != 1.0:
        raise ValueError(f"extension.chip_exponent = {ext.chip_exponent:g}: a ball end mill's chip-size "
                         "effect is its Feng–Menq exponents m_T, m_R (chip exponents are for flat end mills)")
    if coefficients is not None and not isinstance(coefficients, _f.BallEndCoefficients):
        raise ValueError("coefficients: a ball end mill needs BallEndCoefficients or --coefficient-set")
    k = coefficients if coefficients is not None else _f.ball_end_coefficient_set(coefficient_set or "kim_zas_ball12").coefficients
    model = _f.BallEndModel(radius=radius, flutes=flutes, helix=helix, axial_depth=ap, feed_per_tooth=feed_per_tooth,
                            inclination=math.radians(inclination_deg), engagement=engagement, coefficients=k,
                            runout_rho=ext.runout_rho, runout_lambda=ext.runout_lambda)
    return angles, _f.ball_end_forces(model, angles)
