"""The exact Maugis-Dugdale force of a sphere on an elastic half-space, as a nanite model.

nanite (the AFM force-curve fitting library behind PyJibe) fits registered models to the force
against the tip position. Register this one and select it by its key::

    import nanite, tabor.nanite_model
    nanite.model.register_model(tabor.nanite_model)
    idnt.fit_model(model_key="tabor_md", ...)

The tip follows the equilibrium path of a contact under displacement control (the tip position
already contains the cantilever's bending): in contact the Maugis-Dugdale branch, before it
the branch where only the Dugdale zone attracts (the surfaces a gap apart), and no force beyond
the force range. On approach the contact forms where the attracting branch meets the contact
branch at zero radius (exact for lambda <= LAMBDA_D; above it the retract curve stays in contact
down to a smaller indentation, which this approach model does not follow).
"""

import numpy as np

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
    p = np.where(d >= d_end, p, attract)
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
