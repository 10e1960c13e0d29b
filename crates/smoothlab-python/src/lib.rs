//! `smoothlab._native`: the core's front door for Python, under the package in `python/`
//! (`smoothlab.read`, `Mesh.smooth`, `Mesh.stats`, `smoothlab.write`, `smoothlab.render`).
//!
//! A [`Model`] is held here whole; Python sees its arrays (NumPy, moved out of Rust
//! without a copy), its statistics and reports as the JSON the command-line tool prints,
//! and errors as `ValueError` (a bad file or argument; the message names the file's line,
//! the element or the setting) or `OSError` (a file that cannot be read or written).
//! Smoothing and drawing run with the interpreter released, so other Python threads go on.
//!
//! The settings of a run are the core's [`Smoothing`]: each name (the command line's flag,
//! `_` for `-`) calls its builder method, and [`Smoothing::options`] checks them together,
//! so the messages are the core's. A new setting is one arm of `smoothing` and one name
//! in `SETTINGS`.

use std::path::PathBuf;

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyTuple};

use smoothlab::io::{self, CellBlock, MeshArrays, MshVersion, WriteOptions};
use smoothlab::smooth::{Order, Strategy};
use smoothlab::volume::BoundaryRule;
use smoothlab::{Error, Model, ObjectiveKind, Penalty, Smoothing, Target};
use smoothlab_page::lab::picture::{self, Request, View};
use smoothlab_render::{encode_png, Camera, Cut, Metric, Theme};

/// The settings of [`smoothing`] by name, in the command line's order (`smooth --help`).
const SETTINGS: [&str; 13] = [
    "objective",
    "strategy",
    "threshold",
    "passes",
    "order",
    "max_iter",
    "penalty",
    "pass_through_folds",
    "finish",
    "target",
    "slide_curves",
    "boundary",
    "feature_angle",
];

/// An error of the core as Python's: `OSError` for a file that cannot be read or written,
/// `ValueError` for everything else (a bad file, bad arrays, a setting out of range), with
/// `prefix` (the file's name) before the core's words.
fn py_error(e: Error, prefix: Option<&str>) -> PyErr {
    let text = match prefix {
        Some(p) => format!("{p}: {e}"),
        None => e.to_string(),
    };
    match e {
        Error::Io(_) => PyOSError::new_err(text),
        _ => PyValueError::new_err(text),
    }
}

fn value_error(text: impl Into<String>) -> PyErr {
    PyValueError::new_err(text.into())
}

/// The value of an enum setting named by its command-line name, or a `ValueError` that
/// lists the names.
fn named<T: Copy>(
    value: &Bound<'_, PyAny>,
    setting: &str,
    all: &[T],
    name: fn(T) -> &'static str,
) -> PyResult<T> {
    let names: Vec<&str> = all.iter().map(|&v| name(v)).collect();
    let given: String = value.extract().map_err(|_| {
        value_error(format!(
            "{setting}: give a name ({}), not {}",
            names.join(", "),
            shown(value)
        ))
    })?;
    all.iter()
        .copied()
        .find(|&v| name(v) == given)
        .ok_or_else(|| {
            value_error(format!(
                "{setting}: {given:?} is not one of {}",
                names.join(", ")
            ))
        })
}

/// A whole-number setting.
fn whole(value: &Bound<'_, PyAny>, setting: &str) -> PyResult<u32> {
    // not a bool (which Python counts as a number) nor a float (which 3.9 would truncate)
    if value.is_instance_of::<PyBool>() || value.is_instance_of::<PyFloat>() {
        return Err(value_error(format!(
            "{setting}: give a whole number, not {}",
            shown(value)
        )));
    }
    let n: i128 = value.extract().map_err(|_| {
        value_error(format!(
            "{setting}: give a whole number, not {}",
            shown(value)
        ))
    })?;
    u32::try_from(n).map_err(|_| {
        value_error(format!(
            "{setting}: {n} asked: give a positive whole number"
        ))
    })
}

fn number(value: &Bound<'_, PyAny>, setting: &str) -> PyResult<f64> {
    if value.is_instance_of::<PyBool>() {
        return Err(value_error(format!(
            "{setting}: give a number, not {}",
            shown(value)
        )));
    }
    value
        .extract()
        .map_err(|_| value_error(format!("{setting}: give a number, not {}", shown(value))))
}

fn flag(value: &Bound<'_, PyAny>, setting: &str) -> PyResult<bool> {
    value.cast::<PyBool>().map(|b| b.is_true()).map_err(|_| {
        value_error(format!(
            "{setting}: give True or False, not {}",
            shown(value)
        ))
    })
}

/// A value for a message: its repr, cut short.
fn shown(value: &Bound<'_, PyAny>) -> String {
    let r = value
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "that value".into());
    if r.chars().count() > 40 {
        format!("{}…", r.chars().take(40).collect::<String>())
    } else {
        r
    }
}

/// The core's [`Smoothing`] of keyword settings, checked by the core ([`Smoothing::options`]).
fn smoothing(settings: Option<&Bound<'_, PyDict>>) -> PyResult<Smoothing> {
    let mut s = Smoothing::default();
    let Some(settings) = settings else {
        return Ok(s);
    };
    for (key, value) in settings.iter() {
        let name: String = key.extract()?;
        s = match name.as_str() {
            "objective" => s.objective(named(
                &value,
                "objective",
                &ObjectiveKind::ALL,
                ObjectiveKind::name,
            )?),
            "strategy" => s.strategy(named(&value, "strategy", &Strategy::ALL, Strategy::name)?),
            "threshold" => s.threshold(number(&value, "threshold")?),
            "passes" => s.passes(whole(&value, "passes")?),
            "order" => s.order(named(&value, "order", &Order::ALL, Order::name)?),
            "max_iter" => s.max_iter(whole(&value, "max_iter")?),
            "penalty" => s.penalty(named(&value, "penalty", &Penalty::ALL, Penalty::name)?),
            "pass_through_folds" => s.pass_through_folds(flag(&value, "pass_through_folds")?),
            "finish" => s.finish(whole(&value, "finish")?),
            "target" => s.target(named(&value, "target", &Target::ALL, Target::name)?),
            "slide_curves" => s.slide_curves(flag(&value, "slide_curves")?),
            "boundary" => s.boundary(named(&value, "boundary", &BoundaryRule::ALL, BoundaryRule::name)?),
            "feature_angle" => s.feature_angle(number(&value, "feature_angle")?),
            other => {
                return Err(value_error(format!(
                    "no setting named {other:?}: the settings are {}",
                    SETTINGS.join(", ")
                )))
            }
        };
    }
    s.options().map_err(|e| py_error(e, None))?;
    Ok(s)
}

/// The settings' names and, for those that name a choice, the choices: what
/// `Mesh.smooth` takes.
#[pyfunction]
fn settings(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    fn names<T: Copy>(all: &[T], name: fn(T) -> &'static str) -> Vec<&'static str> {
        all.iter().map(|&v| name(v)).collect()
    }
    let out = PyDict::new(py);
    for s in SETTINGS {
        let choices = match s {
            "objective" => Some(names(&ObjectiveKind::ALL, ObjectiveKind::name)),
            "strategy" => Some(names(&Strategy::ALL, Strategy::name)),
            "order" => Some(names(&Order::ALL, Order::name)),
            "penalty" => Some(names(&Penalty::ALL, Penalty::name)),
            "target" => Some(names(&Target::ALL, Target::name)),
            "boundary" => Some(names(&BoundaryRule::ALL, BoundaryRule::name)),
            _ => None,
        };
        out.set_item(s, choices)?;
    }
    Ok(out)
}

/// A mesh the core holds: planar, a surface in 3D or a volume mesh.
#[pyclass(module = "smoothlab._native", name = "Model")]
struct PyModel {
    model: Model,
}

impl PyModel {
    fn mesh_arrays(&self) -> MeshArrays {
        match &self.model {
            Model::Planar(m) => io::mesh_arrays(m),
            Model::Surface(s) => io::mesh_arrays(s),
            Model::Volume(v) => io::volume_arrays(v),
        }
    }
}

#[pymethods]
impl PyModel {
    /// Reads a mesh file (the format by its extension), as `smoothlab` does.
    #[staticmethod]
    fn read(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let name = path.display().to_string();
        let model = py
            .detach(|| io::read(&path))
            .map_err(|e| py_error(e, Some(&name)))?;
        Ok(PyModel { model })
    }

    /// The model a `.vtk` file of these arrays reads as: `points` flat (`dim` a point),
    /// `blocks` a list of `(vtk_type, per_cell, nodes)`, `fixed` one flag a point or None.
    #[staticmethod]
    #[pyo3(signature = (dim, points, blocks, fixed=None))]
    fn from_arrays(
        py: Python<'_>,
        dim: usize,
        points: PyReadonlyArray1<'_, f64>,
        blocks: Vec<(u32, usize, PyReadonlyArray1<'_, u32>)>,
        fixed: Option<PyReadonlyArray1<'_, bool>>,
    ) -> PyResult<Self> {
        let not_flat = |what: &str| value_error(format!("{what}: a contiguous array is needed"));
        let points = points.as_slice().map_err(|_| not_flat("points"))?;
        let cells = blocks
            .iter()
            .map(|(t, k, nodes)| {
                Ok(CellBlock {
                    vtk_type: *t,
                    per_cell: *k,
                    nodes: nodes.as_slice().map_err(|_| not_flat("cells"))?.to_vec(),
                })
            })
            .collect::<PyResult<Vec<_>>>()?;
        let fixed = match &fixed {
            Some(f) => Some(f.as_slice().map_err(|_| not_flat("fixed"))?),
            None => None,
        };
        let model = py
            .detach(|| io::model_from_arrays(dim, points, &cells, fixed))
            .map_err(|e| py_error(e, None))?;
        Ok(PyModel { model })
    }

    /// `"planar"`, `"surface"` or `"volume"`.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.model {
            Model::Planar(_) => "planar",
            Model::Surface(_) => "surface",
            Model::Volume(_) => "volume",
        }
    }

    /// `(points (N·dim,), dim, [(vtk_type, per_cell, nodes (M·k,))], fixed (N,))`: what a
    /// `.vtk` file of the mesh holds, each array moved to NumPy without a copy.
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let a = self.mesh_arrays();
        let blocks = PyList::empty(py);
        for b in a.cells {
            blocks.append((b.vtk_type, b.per_cell, PyArray1::from_vec(py, b.nodes)))?;
        }
        let fixed = PyArray1::from_vec(py, a.fixed);
        (PyArray1::from_vec(py, a.points), a.dim, blocks, fixed).into_pyobject(py)
    }

    /// Smooths the mesh with the settings (the interpreter released meanwhile); the
    /// report as `smoothlab smooth --json` prints it.
    #[pyo3(signature = (**settings))]
    fn smooth(&mut self, py: Python<'_>, settings: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
        let s = smoothing(settings)?;
        let model = &mut self.model;
        let report = py
            .detach(|| model.smooth(&s))
            .map_err(|e| py_error(e, None))?;
        serde_json::to_string(&report).map_err(|e| value_error(e.to_string()))
    }

    /// The statistics as `smoothlab stats --json` prints them.
    fn stats(&self, py: Python<'_>) -> PyResult<String> {
        let model = &self.model;
        let s = py.detach(|| model.stats());
        serde_json::to_string(&s).map_err(|e| value_error(e.to_string()))
    }

    /// Writes the mesh (the format by the extension), as `smoothlab smooth -o` writes it.
    #[pyo3(signature = (path, msh_version=None))]
    fn write(
        &self,
        py: Python<'_>,
        path: PathBuf,
        msh_version: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let msh_version = match msh_version {
            Some(v) => named(v, "msh_version", &MshVersion::ALL, MshVersion::name)?,
            None => MshVersion::default(),
        };
        let model = &self.model;
        py.detach(|| io::write_model_path(model, &path, &WriteOptions { msh_version }))
            .map_err(|e| py_error(e, Some(&path.display().to_string())))
    }

    /// Draws the mesh to a PNG as `smoothlab render IN -o OUT --view VIEW` does (the same
    /// code, `lab::picture`): `options` are its options by their names (`view`, `node`,
    /// `objective`, `metric`, `size`, `dpr`, `strategy`, `threshold`, `passes`, `order`,
    /// `max_iter`, `penalty`, `camera`, `cut`, `theme`), each None for the tool's default.
    #[pyo3(signature = (path, **options))]
    fn render(
        &self,
        py: Python<'_>,
        path: PathBuf,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<()> {
        let r = request(options)?;
        // what the tool leaves unused on these meshes is refused here, never ignored
        let given = |k: &str| {
            options
                .and_then(|o| o.get_item(k).ok().flatten())
                .is_some_and(|v| !v.is_none())
        };
        match &self.model {
            Model::Volume(_) if given("metric") => {
                return Err(value_error(
                    "metric: a volume mesh's cut is coloured by the mean ratio",
                ))
            }
            Model::Surface(_) if given("cut") => {
                return Err(value_error(
                    "cut: it cuts a volume mesh; this mesh is a surface",
                ))
            }
            _ => {}
        }
        let model = self.model.clone();
        let name = path.display().to_string();
        let png = py.detach(|| -> Result<Vec<u8>, String> {
            let start = std::time::Instant::now();
            let clock = move || start.elapsed().as_secs_f64() * 1e3;
            let picture = picture::draw(model, "the mesh", &r, &clock, &|n: &str| n.to_string())?;
            encode_png(&picture).map_err(|e| e.to_string())
        });
        let png = png.map_err(value_error)?;
        std::fs::write(&path, png)
            .map_err(|e| PyOSError::new_err(format!("cannot write {name}: {e}")))
    }

    /// A copy of the mesh (smoothing the copy leaves this one as it is).
    fn copy(&self) -> Self {
        PyModel {
            model: self.model.clone(),
        }
    }
}

/// The picture `render`'s options ask for (None or left out: `smoothlab render`'s default).
fn request(options: Option<&Bound<'_, PyDict>>) -> PyResult<Request> {
    let mut r = Request {
        view: View::Mesh,
        ..Request::default()
    };
    let Some(options) = options else { return Ok(r) };
    for (key, value) in options.iter() {
        let name: String = key.extract()?;
        if value.is_none() {
            continue;
        }
        let text = |what: &str| -> PyResult<String> {
            value
                .extract()
                .map_err(|_| value_error(format!("{name}: give {what}, not {}", shown(&value))))
        };
        match name.as_str() {
            "view" => r.view = named(&value, "view", &View::ALL, View::name)?,
            "node" => r.node = Some(whole(&value, "node")? as usize),
            "objective" => r.sides = picture::sides(&text("old, new or old,new")?, &|n: &str| n.to_string()).map_err(value_error)?,
            "metric" => r.metric = named(&value, "metric", &Metric::ALL, Metric::name)?,
            "size" => {
                let (w, h): (Bound<'_, PyAny>, Bound<'_, PyAny>) = value
                    .extract()
                    .map_err(|_| value_error(format!("size: give (width, height) in pixels, not {}", shown(&value))))?;
                r.size = Some((whole(&w, "size")?, whole(&h, "size")?));
            }
            "dpr" => r.dpr = number(&value, "dpr")? as f32,
            "strategy" => r.strategy = named(&value, "strategy", &Strategy::ALL, Strategy::name)?,
            "threshold" => r.threshold_deg = number(&value, "threshold")?,
            "passes" => r.passes = Some(whole(&value, "passes")?),
            "order" => r.order = named(&value, "order", &Order::ALL, Order::name)?,
            "max_iter" => r.max_iter = whole(&value, "max_iter")?,
            "penalty" => r.penalty = named(&value, "penalty", &Penalty::ALL, Penalty::name)?,
            "camera" => {
                r.camera = Some(Camera::parse(&text("YAW,PITCH[,ZOOM]")?).map_err(|e| value_error(format!("camera: {e}")))?)
            }
            "cut" => r.cut = Some(Cut::parse(&text("AXIS=FRACTION")?).map_err(|e| value_error(format!("cut: {e}")))?),
            "theme" => {
                r.theme = match text("\"light\" or \"dark\"")?.as_str() {
                    "light" => Theme::light(),
                    "dark" => Theme::dark(),
                    other => return Err(value_error(format!("theme: give \"light\" or \"dark\", not {other:?}"))),
                }
            }
            other => {
                return Err(value_error(format!(
                    "render has no option {other:?}: its options are view, node, objective, metric, size, dpr, \
                     strategy, threshold, passes, order, max_iter, penalty, camera, cut, theme"
                )))
            }
        }
    }
    Ok(r)
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<PyModel>()?;
    m.add_function(wrap_pyfunction!(settings, m)?)?;
    m.add("VIEWS", View::ALL.map(View::name).to_vec())?;
    Ok(())
}
