//! The room and channel studies from Python: `_room` and `_channel`, which `depo.room` and
//! `depo.channel` (python/depo/_studies.py) wrap into result objects.
//!
//! A scene is `None` (the built-in one), a path, or a dict with the scene file's keys, turned
//! into a TOML table here; every error is a `ValueError` with the reader's one line naming the
//! key (a value of a type TOML has no place for is a `TypeError` naming it). The study runs
//! on a thread of its own with the GIL released, where `depo.set_num_threads` says
//! (`threads::run_study`), and the calling thread watches it: every 20 ms it checks for
//! signals (Ctrl-C) and passes the progress to the caller's `report(what, done, total)`. On a
//! signal it cancels the study's token ([`depo::tracker::Cancel`]), waits for the study to stop
//! (within a chunk of particles) and raises the signal's exception, `KeyboardInterrupt`: no
//! thread goes on working. Each study returns the command's JSON as text, which the Python
//! side reads, so that `to_dict()` is `depo room --format json` by construction.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use depo::report::channel::{self, ChannelOptions, NearWallChoice};
use depo::report::room::{self, RoomOptions};
use depo::report::Progress;
use depo::scene_file::{self, SceneInput};
use depo::tracker::Cancel;
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::threads::run_study;

/// How often the calling thread looks at the study, for signals and progress.
const POLL: Duration = Duration::from_millis(20);

/// The scene a Python caller gives: `None`, a path (`str` or `os.PathLike`), or a dict.
fn scene_input(scene: Option<&Bound<'_, PyAny>>) -> PyResult<SceneInput> {
    let Some(scene) = scene else { return Ok(SceneInput::BuiltIn) };
    if scene.is_none() {
        return Ok(SceneInput::BuiltIn);
    }
    if let Ok(dict) = scene.cast::<PyDict>() {
        let table = table(dict, "")?;
        let dir = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
        return Ok(SceneInput::Table { table, name: "scene".into(), dir });
    }
    let path = scene.py().import("os")?.call_method1("fspath", (scene,)).map_err(|_| {
        PyTypeError::new_err(format!(
            "scene: expected None, a dict of the scene file's keys or a path, got {}",
            crate::arrays::describe(scene)
        ))
    })?;
    let path: PathBuf = path.extract().map_err(|_| PyTypeError::new_err("scene: expected a str path"))?;
    Ok(SceneInput::Path(path))
}

/// A dict of a scene's keys as a TOML table; `prefix` is the dotted key of the dict, for errors.
/// A key whose value is `None` is left out (the scene's default stands).
fn table(dict: &Bound<'_, PyDict>, prefix: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (key, value) in dict.iter() {
        let Ok(key) = key.cast::<PyString>() else {
            let at = if prefix.is_empty() { "scene".to_string() } else { format!("scene: `{prefix}`") };
            return Err(PyTypeError::new_err(format!("{at}: a key is {}, not a str", crate::arrays::describe(&key))));
        };
        let key: String = key.extract()?;
        let path = if prefix.is_empty() { key.clone() } else { format!("{prefix}.{key}") };
        if let Some(value) = toml_value(&value, &path)? {
            table.insert(key, value);
        }
    }
    Ok(table)
}

/// A Python value as a TOML value; `None` for `None`. Numpy arrays and scalars go through
/// `tolist()`.
fn toml_value(value: &Bound<'_, PyAny>, key: &str) -> PyResult<Option<toml::Value>> {
    if value.is_none() {
        return Ok(None);
    }
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(Some(toml::Value::Boolean(b.is_true())));
    }
    if value.cast::<PyInt>().is_ok() {
        let i: i64 = value.extract().map_err(|_| {
            PyValueError::new_err(format!("scene: `{key}` = {value}: the integer does not fit in 64 bits"))
        })?;
        return Ok(Some(toml::Value::Integer(i)));
    }
    if value.cast::<PyFloat>().is_ok() {
        return Ok(Some(toml::Value::Float(value.extract()?)));
    }
    if let Ok(s) = value.cast::<PyString>() {
        return Ok(Some(toml::Value::String(s.extract()?)));
    }
    if let Ok(d) = value.cast::<PyDict>() {
        return Ok(Some(toml::Value::Table(table(d, key)?)));
    }
    if value.cast::<PyList>().is_ok() || value.cast::<PyTuple>().is_ok() {
        let mut items = Vec::new();
        for (i, item) in value.try_iter()?.enumerate() {
            let item = item?;
            match toml_value(&item, &format!("{key}[{i}]"))? {
                Some(v) => items.push(v),
                None => return Err(PyValueError::new_err(format!("scene: `{key}[{i}]` is None"))),
            }
        }
        return Ok(Some(toml::Value::Array(items)));
    }
    // numpy arrays and scalars (np.float64 is a float already; np.int64, np.bool_ are not).
    if value.hasattr("tolist")? && value.hasattr("dtype")? {
        return toml_value(&value.call_method0("tolist")?, key);
    }
    Err(PyTypeError::new_err(format!(
        "scene: `{key}`: a value of type {} has no TOML value (expected a number, bool, str, list or dict)",
        crate::arrays::describe(value)
    )))
}

/// What the study thread tells the watching thread.
#[derive(Default)]
struct Shared {
    total: AtomicUsize,
    done: AtomicUsize,
    what: Mutex<String>,
    /// Bumped at every start, done and finish, so the watcher sees a change.
    events: AtomicUsize,
    finished: AtomicBool,
}

/// The study's [`Progress`]: counts into [`Shared`] and hands the study the caller's token.
struct Watched {
    shared: Arc<Shared>,
    cancel: Cancel,
}

impl Progress for Watched {
    fn cancel(&self) -> Option<Cancel> {
        Some(self.cancel.clone())
    }
    fn start(&mut self, total: usize, what: &str) {
        *self.shared.what.lock().unwrap_or_else(|e| e.into_inner()) = what.to_string();
        self.shared.total.store(total, Ordering::Relaxed);
        self.shared.done.store(0, Ordering::Relaxed);
        self.shared.events.fetch_add(1, Ordering::Release);
    }
    fn done(&mut self, done: usize) {
        self.shared.done.store(done, Ordering::Relaxed);
        self.shared.events.fetch_add(1, Ordering::Release);
    }
    fn finish(&mut self) {
        self.shared.finished.store(true, Ordering::Relaxed);
        self.shared.events.fetch_add(1, Ordering::Release);
    }
}

/// Runs `study` on a thread of its own with the GIL released, watching it from this one for
/// signals (raised after the study has stopped) and passing its progress to `report`.
fn watched<T: Send>(
    py: Python<'_>,
    report: Option<&Bound<'_, PyAny>>,
    study: impl FnOnce(&mut Watched) -> Result<T, depo::Error> + Send,
) -> PyResult<T> {
    let shared = Arc::new(Shared::default());
    let cancel = Cancel::new();
    let mut progress = Watched { shared: Arc::clone(&shared), cancel: cancel.clone() };
    let outcome = std::thread::scope(|s| {
        let handle = std::thread::Builder::new()
            .name("depo-study".into())
            .spawn_scoped(s, move || run_study(|| study(&mut progress)))
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start the study's thread: {e}")))?;
        let mut seen = 0;
        let mut interrupted = None;
        loop {
            py.detach(|| std::thread::sleep(POLL));
            let finished = handle.is_finished();
            let events = shared.events.load(Ordering::Acquire);
            if let Some(report) = report.filter(|_| events != seen) {
                seen = events;
                let what = shared.what.lock().unwrap_or_else(|e| e.into_inner()).clone();
                let (done, total) = (shared.done.load(Ordering::Relaxed), shared.total.load(Ordering::Relaxed));
                if let Err(e) = report.call1((what, done, total)) {
                    interrupted = Some(e);
                }
            }
            if finished {
                break;
            }
            if interrupted.is_none() {
                interrupted = py.check_signals().err();
            }
            if interrupted.is_some() {
                cancel.cancel();
                break;
            }
        }
        // Joined with the GIL released: the study ends at its next chunk of particles.
        let joined = py.detach(|| handle.join());
        match (interrupted, joined) {
            (Some(e), _) => Err(e),
            (None, Ok(result)) => Ok(result),
            (None, Err(panic)) => {
                let message = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_else(|| "?".into());
                Err(PyRuntimeError::new_err(format!("the study failed: {message}")))
            }
        }
    })?;
    outcome.map_err(|e| match e {
        depo::Error::Invalid(message) => PyValueError::new_err(message),
        depo::Error::Cancelled => PyRuntimeError::new_err("the study was cancelled"),
    })
}

/// Runs a room study: `(json, warnings, seconds)`, `json` the text `depo room --format json`
/// prints for the same scene and seed, `warnings` the scene reader's, `seconds` the runs'
/// wall-clock time. `report(what, done, total)` is called on this thread as sizes complete.
#[pyfunction]
#[pyo3(signature = (scene = None, seed = None, report = None))]
pub fn _room(
    py: Python<'_>,
    scene: Option<&Bound<'_, PyAny>>,
    seed: Option<u64>,
    report: Option<&Bound<'_, PyAny>>,
) -> PyResult<(String, Vec<String>, f64)> {
    let input = scene_input(scene)?;
    // Read here first: a bad scene is a ValueError before any thread starts, with its warnings.
    let warnings = scene_file::room_scene(&input).map_err(|e| PyValueError::new_err(e.to_string()))?.warnings;
    let options = RoomOptions { seed, ..RoomOptions::new(input) };
    let (json, seconds) = watched(py, report, |progress| {
        let result = room::study(&options, progress)?;
        Ok((room::json::to_json(&result)?, result.seconds))
    })?;
    Ok((json, warnings, seconds))
}

/// Runs a channel study: one `(name, json, seconds)` per run (two with `near_wall="all"`),
/// `json` the text `depo channel --format json` prints for that run.
#[pyfunction]
#[pyo3(signature = (scene = None, seed = None, tau_plus = None, near_wall = None, report = None))]
pub fn _channel(
    py: Python<'_>,
    scene: Option<&Bound<'_, PyAny>>,
    seed: Option<u64>,
    tau_plus: Option<Vec<f64>>,
    near_wall: Option<&str>,
    report: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<(String, String, f64)>> {
    let near_wall = match near_wall {
        None => None,
        Some("resolved") => Some(NearWallChoice::Resolved),
        Some("wall-function") => Some(NearWallChoice::WallFunction),
        Some("all") => Some(NearWallChoice::All),
        Some(other) => {
            return Err(PyValueError::new_err(format!(
                "near_wall = {other:?}: expected \"resolved\", \"wall-function\" or \"all\""
            )))
        }
    };
    let input = scene_input(scene)?;
    scene_file::channel_scene(&input).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let options = ChannelOptions { seed, tau_plus, near_wall, ..ChannelOptions::new(input) };
    watched(py, report, |progress| {
        let result = channel::study(&options, progress)?;
        result
            .runs
            .iter()
            .map(|run| Ok((run.name.to_string(), channel::json::to_json(run)?, run.seconds)))
            .collect::<Result<Vec<_>, depo::Error>>()
    })
    // The tau+ list's messages name the command's flag; here it is the argument.
    .map_err(|e| {
        if e.is_instance_of::<PyValueError>(py) {
            let message = e.value(py).to_string().replace("--tau-plus", "tau_plus");
            PyValueError::new_err(message)
        } else {
            e
        }
    })
}
