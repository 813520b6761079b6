"""Issue 37 item 7: fits checked. SciPy least_squares' status is read (non-converged fits are
reported in the candidate and the notes), and the cross-validation folds start from the model
without the effect, not from the all-data optimum; what a fold fits besides the effect's parameters
(the volumetric frame, start values read off the residual) sees its fitting points only."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import netshape.discrepancy as nd
from netshape.discrepancy.catalogue import EffectFit

from generators import force_bundle, structured_volumetric_bundle, volumetric_bundle


class ProbeOffset(nd.Effect):
    """An offset of the probe along X [µm] in the second experiment (re-seated with the longer tool):
    the user effect of docs/discrepancy.md made per experiment, since an offset common to all points
    is the registered frame's translation."""

    name, kind, parameters, covariate = "probe_offset_t", "volumetric_error", ("dx_um",), "position"

    def starts(self, problem, spec):
        return [np.zeros(1)]

    def apply(self, problem, spec, x):
        def add(exp, pts, v=float(x[0]), first=problem.experiments[0].file):
            out = np.zeros((len(pts), 3))
            out[:, 0] = v * 1e-3 if exp.file != first else 0.0
            return out

        return dataclasses.replace(spec, additive=spec.additive + (add,))

    def parameters_of(self, x):
        return {"dx_um": float(x[0])}


class Stalled(ProbeOffset):
    """The same, but its fit reports SciPy status 0 (max_nfev reached)."""

    name = "stalled_offset"

    def fit(self, problem, spec, train=None):
        f = super().fit(problem, spec, train)
        return dataclasses.replace(f, status=0)


@pytest.fixture
def offset_bundle(tmp_path):
    vb = volumetric_bundle(tmp_path / "v")
    for name in ("v2.csv",):
        data = np.loadtxt(vb / name, delimiter=",", skiprows=1)
        data[:, 3] += 0.004
        np.savetxt(vb / name, data, delimiter=",", header="x_mm,y_mm,z_mm,ex_mm,ey_mm,ez_mm,t_s,direction",
                   comments="")
    return vb


def test_least_squares_status_is_recorded(offset_bundle):
    p = nd.make_problem(nd.load_bundle(offset_bundle))
    s = p.initial_spec()
    eff = ProbeOffset()
    p.least_squares(lambda x: eff.apply(p, s, x), [np.zeros(1)], (-np.inf, np.inf))
    assert p.last_status > 0
    p.least_squares(lambda x: eff.apply(p, s, x), [np.zeros(1)], (-np.inf, np.inf), max_nfev=1)
    assert p.last_status == 0
    f = eff.fit(p, s)
    assert f.status is not None and f.status > 0


def test_non_converged_fit_is_reported(offset_bundle):
    nd.register_effect(Stalled())
    try:
        d = nd.diagnose(offset_bundle, effects=["stalled_offset", "squareness"])
    finally:
        nd.unregister_effect("volumetric_error", "stalled_offset")
    c = next(c for c in d.candidates if c["effect"] == "stalled_offset")
    assert c["converged"] is False
    assert any("stalled_offset: the fit did not converge (least_squares status 0" in n for n in d.notes)
    sq = next(c for c in d.candidates if c["effect"] == "squareness")
    assert sq["converged"] is True and sq["cv_folds_not_converged"] == 0


def test_cv_folds_start_from_the_model_without_the_effect(offset_bundle, monkeypatch):
    """Before, every fold started from the all-data optimum (4 µm here), which has seen the test points."""
    starts = []
    orig = nd.VolumetricProblem.cv_rms

    def spy(self, make_spec, x0, bounds):
        if callable(x0):  # an effect's start, evaluated per fold on the fold's fitting points
            starts.append(np.array(x0(), float))
        return orig(self, make_spec, x0, bounds)

    monkeypatch.setattr(nd.VolumetricProblem, "cv_rms", spy)
    nd.register_effect(ProbeOffset())
    try:
        d = nd.diagnose(offset_bundle, effects=["probe_offset_t", "thermal_drift"])
    finally:
        nd.unregister_effect("volumetric_error", "probe_offset_t")
    assert d.effect == "probe_offset_t" and abs(d.parameters["dx_um"] - 4.0) < 0.2
    assert np.array_equal(starts[0], [0.0])  # probe offset: 0, not the fitted 4 µm
    assert starts[1][0] == 0.0  # thermal drift: rate 0 (no drift)


def test_held_out_points_shape_neither_the_frame_nor_the_starts(tmp_path):
    """A fold's held-out points spoiled (volumetric: 1 mm added; forces: a 2400 Hz mode's response
    ×100 added) change neither the fold's registered frame nor the start values read off the
    residual (cyclic_error's periodogram, structural_mode's frequency scan); over all points they do.
    Before, all three were fitted on all points."""
    from netshape.discrepancy.force_catalogue import StructuralMode
    from netshape.discrepancy.volumetric_effects import CyclicError

    b = structured_volumetric_bundle(tmp_path / "v", extra=[("periodic", "ex", "x", 4e-3, 40.0)],
                                     grid=(33, 4, 2))
    fb = force_bundle(tmp_path / "f", mode=(1500.0, 0.05))

    def volumetric(p, s):
        return (*p.frame_of(s), *CyclicError()._starts_axis(p, s, "X"))

    def other_mode(p, s):  # 100 × the response of another mode
        return [100.0 * (o - q) for o, q in zip(p.predict(dataclasses.replace(s, mode=(2400.0, 0.03))),
                                                p.predict(s))]

    for problem, read, spoil in [
        (nd.make_problem(nd.load_bundle(b)), volumetric, lambda p, s: [np.ones_like(m) for m in p.measured]),
        (nd.make_problem(nd.load_bundle(fb)), lambda p, s: StructuralMode().starts(p, s), other_mode),
    ]:
        s = problem.initial_spec()
        train, test = problem.folds()[0]
        problem.fit_mask = train
        before = read(problem, s)
        problem.measured = [m + np.where(t[:, None], d, 0.0)
                            for m, t, d in zip(problem.measured, test, spoil(problem, s))]
        assert all(np.allclose(u, v, rtol=1e-9, atol=1e-12) for u, v in zip(before, read(problem, s)))
        problem.fit_mask = None
        assert not all(np.allclose(u, v, rtol=1e-6, atol=1e-9) for u, v in zip(before, read(problem, s)))
