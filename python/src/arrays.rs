//! Borrowing numpy arrays for the kernel.
//!
//! A contiguous 1-D array is borrowed as a slice, without a copy: the kernel reads and writes
//! the caller's memory. Any other 1-D view (a column of an `(n, 3)` array, a reversed or
//! stepped slice) is gathered into a contiguous scratch copy, goes through the same kernel, and
//! is scattered back on success, so its results are those of the contiguous case bit for bit.
//! rust-numpy's borrow checker refuses an output that shares memory with any other array of
//! the call (two views of the same column, a velocity that is also the radius), which the C
//! ABI's overlap check refuses likewise.

use numpy::{
    BorrowError, Element, PyArray1, PyArrayDescrMethods, PyArrayMethods, PyReadonlyArray1, PyReadwriteArray1,
    PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

/// The dtype's name of an array, or the Python type's name of anything else, for messages.
pub fn describe(obj: &Bound<'_, PyAny>) -> String {
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        let dtype = array.dtype().str().map(|s| s.to_string()).unwrap_or_else(|_| "?".into());
        format!("a {}-D array of {dtype}", array.ndim())
    } else {
        obj.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "?".into())
    }
}

/// `obj` as a 1-D array of `T`: a `TypeError` naming `name` when it is not a numpy array or not
/// of dtype `T`, a `ValueError` when it has another number of dimensions.
pub fn typed<'py, T: Element>(obj: &Bound<'py, PyAny>, name: &str, dtype: &str) -> PyResult<Bound<'py, PyArray1<T>>> {
    if let Ok(array) = obj.cast::<PyArray1<T>>() {
        return Ok(array.clone());
    }
    match obj.cast::<PyUntypedArray>() {
        Ok(array) if array.ndim() != 1 && array.dtype().is_equiv_to(&numpy::dtype::<T>(obj.py())) => {
            Err(PyValueError::new_err(format!("{name}: expected a 1-D array, got {} dimensions", array.ndim())))
        }
        _ => Err(PyTypeError::new_err(format!("{name}: expected a 1-D numpy array of {dtype}, got {}", describe(obj)))),
    }
}

fn borrow_error(name: &str, e: BorrowError) -> PyErr {
    match e {
        BorrowError::NotWriteable => PyValueError::new_err(format!("{name} is read-only")),
        _ => PyValueError::new_err(format!("{name} shares memory with another array of the call (or is in use)")),
    }
}

/// An array the kernel writes: the caller's memory when contiguous, else a gathered copy that
/// [`Output::finish`] scatters back.
pub struct Output<'py, T: Element> {
    guard: PyReadwriteArray1<'py, T>,
    scratch: Option<Vec<T>>,
}

impl<'py, T: Element + Copy> Output<'py, T> {
    pub fn new(array: &Bound<'py, PyArray1<T>>, name: &str) -> PyResult<Self> {
        let guard = array.try_readwrite().map_err(|e| borrow_error(name, e))?;
        let scratch = if guard.as_slice().is_ok() { None } else { Some(guard.as_array().to_vec()) };
        Ok(Self { guard, scratch })
    }

    pub fn len(&self) -> usize {
        self.guard.len()
    }

    /// The values as one contiguous slice.
    pub fn slice(&mut self) -> &mut [T] {
        match &mut self.scratch {
            Some(values) => values,
            None => self.guard.as_slice_mut().expect("checked contiguous in Output::new"),
        }
    }

    /// Writes a gathered copy back into the caller's view.
    pub fn finish(mut self) {
        if let Some(values) = self.scratch.take() {
            for (to, from) in self.guard.as_array_mut().iter_mut().zip(values) {
                *to = from;
            }
        }
    }
}

/// An array the kernel only reads: the caller's memory when contiguous, else a gathered copy.
pub struct Input<'py, T: Element> {
    guard: PyReadonlyArray1<'py, T>,
    scratch: Option<Vec<T>>,
}

impl<'py, T: Element + Copy> Input<'py, T> {
    pub fn new(array: &Bound<'py, PyArray1<T>>, name: &str) -> PyResult<Self> {
        let guard = array.try_readonly().map_err(|e| borrow_error(name, e))?;
        let scratch = if guard.as_slice().is_ok() { None } else { Some(guard.as_array().to_vec()) };
        Ok(Self { guard, scratch })
    }

    /// The values as one contiguous slice.
    pub fn slice(&self) -> &[T] {
        match &self.scratch {
            Some(values) => values,
            None => self.guard.as_slice().expect("checked contiguous in Input::new"),
        }
    }
}
