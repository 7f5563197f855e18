//! The package's exceptions, and the solver's errors mapped onto them with the CLI's text.

use pyo3::create_exception;
use pyo3::exceptions::{
    PyKeyboardInterrupt, PyMemoryError, PyOSError, PyRuntimeError, PyValueError,
};
use pyo3::PyErr;

create_exception!(
    impact,
    SceneError,
    PyValueError,
    "A scene that cannot be read, parsed or validated; the message is the CLI's \
     (file:line:col: field = value: what is allowed)."
);
create_exception!(
    impact,
    RunError,
    PyRuntimeError,
    "A run that could not go on (instability, the contact law's maximum exceeded); the \
     message names the step and time, as the CLI's."
);
create_exception!(
    impact,
    VerifyError,
    PyValueError,
    "The verification matrix could not start (a case does not load or lint, no case matches)."
);

/// The solver's error as a Python exception with the same message as `impact simulate`.
pub fn to_py(e: impact_solver::Error) -> PyErr {
    use impact_solver::Error as E;
    let message = e.to_string();
    match e {
        E::ReadScene { .. } | E::ParseScene { .. } | E::InvalidScene(_) | E::Override { .. } => {
            SceneError::new_err(message)
        }
        E::Run { .. } => RunError::new_err(message),
        E::Interrupted { .. } => PyKeyboardInterrupt::new_err(message),
        E::TooLarge { .. } => PyMemoryError::new_err(message),
        E::OutputFolder { .. } | E::WriteOutput { .. } => PyOSError::new_err(message),
    }
}
