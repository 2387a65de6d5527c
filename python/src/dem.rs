//! `tabor.dem_law`: the force-overlap law for particle (DEM) codes (`tabor dem-law`, the C
//! ABI's law) on NumPy arrays.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1, PyReadwriteArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tabor::dem::{DemLaw, Pair, DEFAULT_OVERLAP_MAX};
use tabor::law::ContactLaw;

/// A law, normalised (`lam`) or of a pair in SI units (a scene).
#[pyclass(name = "DemLaw", module = "tabor._tabor", frozen)]
pub struct PyDemLaw {
    law: DemLaw,
    meniscus: Option<tabor::scene::humidity::Meniscus>,
    /// N per unit load and m per approach unit (1 and 1 where normalised).
    force: f64,
    length: f64,
    si: bool,
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

#[pyfunction]
#[pyo3(signature = (lam=None, scene_json=None, overlap_max=None, stress_ratio=None, range_ratio=None))]
pub fn dem_law(
    lam: Option<f64>,
    scene_json: Option<String>,
    overlap_max: Option<f64>,
    stress_ratio: Option<f64>,
    range_ratio: Option<f64>,
) -> PyResult<PyDemLaw> {
    if scene_json.is_some() && (stress_ratio.is_some() || range_ratio.is_some()) {
        return Err(value_error(
            "stress_ratio and range_ratio are for a normalised law (lam): a scene gives its meniscus by its humidity",
        ));
    }
    match (lam, scene_json) {
        (Some(l), None) => {
            let law = ContactLaw::new(l, stress_ratio, range_ratio).map_err(value_error)?;
            let law = DemLaw::of_law(law, overlap_max.unwrap_or(DEFAULT_OVERLAP_MAX))
                .map_err(|e| value_error(format!("lam = {l}: {e}")))?;
            Ok(PyDemLaw {
                law,
                meniscus: None,
                force: 1.0,
                length: 1.0,
                si: false,
            })
        }
        (None, Some(j)) => {
            let s: tabor::scene::SceneInput = serde_json::from_str(&j)
                .map_err(|e| value_error(format!("not a valid scene: {e}")))?;
            let p = Pair::from_scene(&s, overlap_max).map_err(value_error)?;
            Ok(PyDemLaw {
                force: p.force_scale,
                length: p.length_scale,
                meniscus: p.meniscus,
                law: p.law,
                si: true,
            })
        }
        _ => Err(value_error(
            "give lam (a normalised law) or scene (a pair in SI units), one of them",
        )),
    }
}

#[pymethods]
impl PyDemLaw {
    /// The law's marks, scales and table, in its units.
    #[getter]
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (l, f, law) = (self.length, self.force, &self.law);
        let d = PyDict::new(py);
        d.set_item(
            "units",
            if self.si {
                "SI: m, N, N/m, J"
            } else {
                "normalised: pi w R, (pi^2 w^2 R / K^2)^(1/3)"
            },
        )?;
        d.set_item("model", law.law.model().name())?;
        d.set_item("lambda", law.lambda)?;
        if let ContactLaw::SolidAndMeniscus(z) = law.law {
            d.set_item("stress_ratio", z.stress_ratio)?;
            d.set_item("range_ratio", z.range_ratio)?;
        }
        if let Some(m) = &self.meniscus {
            let md = PyDict::new(py);
            md.set_item("kelvin_radius_m", m.kelvin_radius_m)?;
            md.set_item("laplace_pressure_pa", m.laplace_pressure_pa)?;
            md.set_item("range_m", m.range_m)?;
            md.set_item("work_of_adhesion_j_m2", m.work_of_adhesion_j_m2)?;
            md.set_item("lambda", m.lambda)?;
            d.set_item("meniscus", md)?;
        }
        d.set_item("histories", law.stretch_count())?;
        d.set_item("attraction_from", law.attraction_from * l)?;
        d.set_item("jump_in", law.delta_in * l)?;
        d.set_item("jump_out", law.delta_out * l)?;
        d.set_item("jump_out_force", law.disp_pulloff * f)?;
        d.set_item("non_contact_end", law.delta_nc.map(|x| x * l))?;
        d.set_item("pulloff_force", law.load_pulloff * f)?;
        d.set_item(
            "loop_energy",
            law.loop_area(law.overlap_max).map(|e| e * f * l),
        )?;
        d.set_item("table_error", law.error)?;
        d.set_item("table_nodes", law.nodes)?;
        d.set_item("overlap_max", law.overlap_max * l)?;
        d.set_item("force_scale", f)?;
        d.set_item("length_scale", l)?;
        Ok(d)
    }

    /// Forces and stiffnesses at `overlap` for contacts whose history codes are `history`
    /// (uint8, updated in place).
    fn eval<'py>(
        &self,
        py: Python<'py>,
        overlap: PyReadonlyArray1<'py, f64>,
        mut history: PyReadwriteArray1<'py, u8>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>)> {
        let x = overlap.as_slice()?;
        let h = history.as_slice_mut()?;
        if x.len() != h.len() {
            return Err(value_error(format!(
                "overlap has {} values and history {}: give one history code per contact",
                x.len(),
                h.len()
            )));
        }
        let n = self.law.stretch_count();
        if let Some(i) = h.iter().position(|&c| self.law.history(c).is_none()) {
            return Err(value_error(format!(
                "history[{i}] = {} is not a history code of this law: give 0 (apart) for a new contact, or a code the law returned (below {n})",
                h[i]
            )));
        }
        let (mut f, mut k) = (Vec::with_capacity(x.len()), Vec::with_capacity(x.len()));
        for (d, code) in x.iter().zip(h.iter_mut()) {
            let mut b = self.law.history(*code).unwrap_or_default();
            let e = self.law.eval(d / self.length, &mut b);
            *code = b.code();
            f.push(e.load * self.force);
            k.push(e.stiffness * self.force / self.length);
        }
        Ok((f.into_pyarray(py), k.into_pyarray(py)))
    }

    /// The branch of each history code: 0 free, 1 non-contact, 2 contact.
    fn branches<'py>(
        &self,
        py: Python<'py>,
        history: PyReadonlyArray1<'py, u8>,
    ) -> PyResult<Bound<'py, PyArray1<u8>>> {
        let h = history.as_slice()?;
        let out = h
            .iter()
            .enumerate()
            .map(|(i, &c)| {
                self.law
                    .history(c)
                    .map(|h| self.law.branch(h) as u8)
                    .ok_or_else(|| {
                        value_error(format!(
                            "history[{i}] = {c} is not a history code of this law (below {})",
                            self.law.stretch_count()
                        ))
                    })
            })
            .collect::<PyResult<Vec<u8>>>()?;
        Ok(out.into_pyarray(py))
    }

    /// The pair driven from `overlap_min` to `overlap_max` and back at `points` overlaps each
    /// way: `{"approach": {"overlap", "force"}, "retract": {...}}`.
    fn drive<'py>(
        &self,
        py: Python<'py>,
        overlap_min: f64,
        overlap_max: f64,
        points: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        if !(2..=1_000_000).contains(&points) {
            return Err(value_error(format!(
                "points = {points} is outside 2..1000000: give at least two overlaps each way"
            )));
        }
        if !(overlap_min.is_finite() && overlap_max.is_finite() && overlap_min < overlap_max) {
            return Err(value_error(format!(
                "overlap_min = {overlap_min}, overlap_max = {overlap_max}: give finite overlaps, the smallest first"
            )));
        }
        let (app, ret) =
            self.law
                .drive(overlap_min / self.length, overlap_max / self.length, points);
        let out = PyDict::new(py);
        for (name, half) in [("approach", app), ("retract", ret)] {
            let d = PyDict::new(py);
            let x: Vec<f64> = half.iter().map(|(x, _)| x * self.length).collect();
            let f: Vec<f64> = half.iter().map(|(_, e)| e.load * self.force).collect();
            d.set_item("overlap", x.into_pyarray(py))?;
            d.set_item("force", f.into_pyarray(py))?;
            out.set_item(name, d)?;
        }
        Ok(out)
    }

    /// The energy lost in one slow cycle to `overlap_max` and back (None where it could not
    /// be computed).
    fn loop_energy(&self, overlap_max: f64) -> Option<f64> {
        self.law
            .loop_area(overlap_max / self.length)
            .map(|a| a * self.force * self.length)
    }
}
