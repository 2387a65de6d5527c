"""The exact Maugis-Dugdale force of a sphere, or of a tip of another shape, on an elastic
half-space, as nanite models.

nanite (the AFM force-curve fitting library behind PyJibe) fits registered models to the force
against the tip position. Register this one and select it by its key::

    import nanite, tabor.nanite_model
    nanite.model.register_model(tabor.nanite_model)
    idnt.fit_model(model_key="tabor_md", ...)

The tip follows the equilibrium path of a contact under displacement control (the tip position
already contains the cantilever's bending): in contact the Maugis-Dugdale branch, before it
the branch where only the Dugdale zone attracts (the surfaces a gap apart), and no force beyond
the force range. On approach the contact forms where the attracting branch meets the contact
branch at zero radius; for lambda^3 > 9/32 (lambda > 0.655) that meeting lies beyond the range,
and the surfaces jump into contact where the gap closes within it (the retract curve stays in
contact down to a smaller indentation, which this approach model does not follow).

The tips of docs/PHYSICS.md section 12 are models too, on the same path (the tip's exact
Maugis-Dugdale law in its units): ``cone`` (key ``tabor_md_cone``, half-angle ``alpha`` in
degrees, as nanite's ``hertz_cone``), ``pyr3s`` and ``pyr4s`` (``tabor_md_pyr3s``,
``tabor_md_pyr4s``: three- and four-sided pyramids of face angle ``alpha``, as the cone of the
same area function), and :func:`for_tip` for any fixed tip a scene takes (a power law, a capped
cone, a measured profile)::

    nanite.model.register_model(tabor.nanite_model.cone)
    nanite.model.register_model(tabor.nanite_model.for_tip(
        {"shape": "capped_cone", "radius_m": 20e-9, "half_angle_deg": 20}, "my_tip"))
"""

import json
import types

import numpy as np

from . import _tabor, _tip_text
from . import solve as _solve

#: LJ-matched Dugdale stress: s0 = LJ_STRESS * w / z0.
LJ_STRESS = 16.0 / (9.0 * np.sqrt(3.0))


def get_parameter_defaults():
    """Default parameters (an lmfit.Parameters); order as ``parameter_keys``."""
    import lmfit
    params = lmfit.Parameters()
    params.add("E", value=3e3, min=0)
    params.add("w", value=1e-4, min=0)
    params.add("z0", value=0.3e-9, min=0, vary=False)
    params.add("R", value=10e-6, min=0, vary=False)
    params.add("nu", value=.5, min=0, max=0.5, vary=False)
    params.add("contact_point", value=0)
    params.add("baseline", value=0)
    return params


def scales(E, w, z0, R, nu):
    """(lambda, force unit pi w R, approach unit) of a sphere of radius R on a half-space of
    modulus E and Poisson ratio nu (rigid tip), work of adhesion w, Lennard-Jones range z0."""
    k = 4.0 / 3.0 * E / (1.0 - nu ** 2)
    s0 = LJ_STRESS * w / z0
    lam = 2.0 * s0 * (R / (np.pi * w * k ** 2)) ** (1.0 / 3.0)
    return lam, np.pi * w * R, (np.pi ** 2 * w ** 2 * R / k ** 2) ** (1.0 / 3.0)


def md_force(delta, E, w, z0, R, nu, contact_point=0, baseline=0):
    r"""Maugis-Dugdale force of a spherical indenter (exact, tabor)

    The indentation is :math:`\delta = \mathrm{contact\_point} - x` (x the tip position);
    in units of :math:`(\pi^2 w^2 R / K^2)^{1/3}` with :math:`K = \frac{4}{3} E/(1-\nu^2)`
    it fixes the state on the Maugis-Dugdale curve (displacement control), and the force is
    :math:`\bar P \, \pi w R` + baseline. Before contact: the Dugdale zone alone,
    :math:`\bar P = -(\pi\lambda/2) C^2` with
    :math:`\bar D = C^2/2 - (8\lambda/(3\pi)) C - 2/(\pi\lambda)`, and no force where the gap
    exceeds the Dugdale range. :math:`\lambda = 2 s_0 (R/(\pi w K^2))^{1/3}`,
    :math:`s_0 = 16 w / (9\sqrt{3} z_0)` (Lennard-Jones matched).

    Parameters
    ----------
    delta: 1d ndarray
        Tip position [m]
    E: float
        Young's modulus of the sample [Pa]
    w: float
        Work of adhesion [J/m²]
    z0: float
        Lennard-Jones equilibrium spacing (range of the surface forces) [m]
    R: float
        Tip radius [m]
    nu: float
        Poisson's ratio of the sample
    contact_point: float
        Indentation offset [m]
    baseline: float
        Force offset [N]

    Returns
    -------
    F: 1d ndarray
        Force [N]

    References
    ----------
    Maugis (1992), Johnson & Greenwood (1997); solved by tabor.
    """
    x = np.asarray(delta, dtype=float)
    lam, force_unit, approach_unit = scales(E, w, z0, R, nu)
    d = (contact_point - x) / approach_unit
    r = _solve(lam, approach=d)
    p = np.where(r["status"] == "ok", r["load"], np.nan)
    # The A -> 0 end of the contact branch: below it the attracting (non-contact) branch.
    c_end = 2.0 / (2.0 * (np.pi - 2.0) * lam ** 2 / 3.0
                   + np.sqrt((2.0 * (np.pi - 2.0) * lam ** 2 / 3.0) ** 2 + np.pi * lam))
    d_end = -(4.0 / 3.0) * lam * c_end
    b = 8.0 * lam / (3.0 * np.pi)
    free = d + 2.0 / (np.pi * lam)
    c = b + np.sqrt(np.maximum(b * b + 2.0 * free, 0.0))
    attract = np.where(free >= 0.0, -(np.pi * lam / 2.0) * np.minimum(c, c_end) ** 2, 0.0)
    # Contact from the zone's end on; where that end lies beyond the range (lambda^3 > 9/32, the
    # zone alone has no stable state to approach on), from the free end, where the gap closes
    # within the range and the surfaces jump into contact.
    p = np.where(d >= max(d_end, -2.0 / (np.pi * lam)), p, attract)
    return force_unit * np.nan_to_num(p, nan=0.0) + baseline


model_doc = md_force.__doc__
model_func = md_force
model_key = "tabor_md"
model_name = "Maugis-Dugdale sphere, exact (tabor)"
parameter_keys = ["E", "w", "z0", "R", "nu", "contact_point", "baseline"]
parameter_names = ["Young's Modulus", "Work of Adhesion", "Force Range z0", "Tip Radius",
                   "Poisson's Ratio", "Contact Point", "Force Baseline"]
parameter_units = ["Pa", "J/m²", "m", "m", "", "m", "N"]
valid_axes_x = ["tip position"]
valid_axes_y = ["force"]


def tip_md_force(delta, tip, E, w, z0, nu, contact_point=0, baseline=0):
    """The Maugis-Dugdale force of the tip ``tip`` (a scene's ``"tip"`` object, SI units) at
    the tip positions ``delta``, on the path the sphere's model follows: no force while the gap
    exceeds the range, the Dugdale zone alone until it meets the contact (A -> 0), then the
    contact (docs/PHYSICS.md section 12; ``Tip::approach_state``). E is Young's modulus (E* =
    E/(1 - nu^2)), z0 the Lennard-Jones range (s0 = LJ_STRESS w / z0)."""
    x = np.asarray(delta, dtype=float)
    scene = _tip_text({"e_star_pa": E / (1.0 - nu ** 2), "work_of_adhesion_j_m2": w,
                       "s0_pa": LJ_STRESS * w / z0, "tip": tip})
    u = _tabor.tip_units(scene)
    d = np.ascontiguousarray((contact_point - x) / u["approach_m"]).ravel()
    r = _tabor.solve_tip(scene, np.full(d.shape, float(u["lambda"])), d, "approach_in")
    # A lambda outside the tip law's 1e-3..1e3 (status invalid_input) gives NaN, which lmfit
    # refuses, not a flat curve; beyond A = e^60 (no_contact) no force.
    code = np.asarray(r["status_code"]).reshape(x.shape)
    p = np.where(code == 0, np.asarray(r["load"]).reshape(x.shape), 0.0)
    p = np.where(code == 3, np.nan, p)
    return u["force_n"] * p + baseline


_TIP_KEYS = ["E", "w", "z0", "nu", "contact_point", "baseline"]
_TIP_NAMES = ["Young's Modulus", "Work of Adhesion", "Force Range z0", "Poisson's Ratio",
              "Contact Point", "Force Baseline"]
_TIP_UNITS = ["Pa", "J/m²", "m", "", "m", "N"]


def _model(key, name, func, keys, names, units, defaults):
    """A nanite model object (what nanite reads from a model module)."""
    m = types.ModuleType(key)
    m.model_func, m.model_doc, m.model_key, m.model_name = func, func.__doc__, key, name
    m.parameter_keys, m.parameter_names, m.parameter_units = keys, names, units
    m.valid_axes_x, m.valid_axes_y = ["tip position"], ["force"]

    def get_parameter_defaults():
        import lmfit
        params = lmfit.Parameters()
        for k, (value, vary, lo, hi) in defaults.items():
            params.add(k, value=value, vary=vary, min=lo, max=hi)
        return params

    m.get_parameter_defaults = get_parameter_defaults
    return m


_DEFAULTS = {"E": (3e3, True, 0, np.inf), "w": (1e-4, True, 0, np.inf),
             "z0": (0.3e-9, False, 0, np.inf), "nu": (0.5, False, 0, 0.5),
             "contact_point": (0.0, True, -np.inf, np.inf),
             "baseline": (0.0, True, -np.inf, np.inf)}


def for_tip(tip, key, name=None):
    """A nanite model of the exact Maugis-Dugdale force of a fixed tip (a scene's ``"tip"``
    object: a power law, a capped cone, a measured profile, ...), under ``key``; its parameters
    are the sphere model's without R."""
    tip = dict(tip)

    def force(delta, E, w, z0, nu, contact_point=0, baseline=0):
        return tip_md_force(delta, tip, E, w, z0, nu, contact_point, baseline)

    shown = json.dumps(tip, default=str)[:200]
    force.__doc__ = (f"Maugis-Dugdale force of the tip {shown} (exact, tabor)"
                     "\n\n" + (tip_md_force.__doc__ or ""))
    return _model(key, name or f"Maugis-Dugdale tip, exact (tabor): {tip.get('shape')}", force,
                  _TIP_KEYS, _TIP_NAMES, _TIP_UNITS, _DEFAULTS)


def _angled(key, name, tip_of, doc):
    def force(delta, E, w, z0, alpha, nu, contact_point=0, baseline=0):
        return tip_md_force(delta, tip_of(alpha), E, w, z0, nu, contact_point, baseline)

    force.__doc__ = doc
    defaults = dict(_DEFAULTS)
    defaults = {k: defaults[k] for k in ("E", "w", "z0")}
    defaults["alpha"] = (20.0, False, 0, 90)
    defaults.update({k: _DEFAULTS[k] for k in ("nu", "contact_point", "baseline")})
    keys = ["E", "w", "z0", "alpha", "nu", "contact_point", "baseline"]
    names = _TIP_NAMES[:3] + ["Half Cone Angle" if "cone" in key else "Face Angle"] + _TIP_NAMES[3:]
    units = _TIP_UNITS[:3] + ["°"] + _TIP_UNITS[3:]
    return _model(key, name, force, keys, names, units, defaults)


cone = _angled("tabor_md_cone", "Maugis-Dugdale cone, exact (tabor)",
               lambda a: {"shape": "cone", "half_angle_deg": a},
               "Maugis-Dugdale force of a cone of half-angle alpha (degrees; exact, tabor)")
pyr3s = _angled("tabor_md_pyr3s", "Maugis-Dugdale three-sided pyramid, exact (tabor)",
                lambda a: {"shape": "pyramid", "faces": 3, "face_angle_deg": a},
                "Maugis-Dugdale force of a three-sided pyramid of face angle alpha (degrees), "
                "as the cone of the same area function (exact, tabor)")
pyr4s = _angled("tabor_md_pyr4s", "Maugis-Dugdale four-sided pyramid, exact (tabor)",
                lambda a: {"shape": "pyramid", "faces": 4, "face_angle_deg": a},
                "Maugis-Dugdale force of a four-sided pyramid of face angle alpha (degrees), "
                "as the cone of the same area function (exact, tabor)")
