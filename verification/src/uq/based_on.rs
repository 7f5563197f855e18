//! What a study shares with those `based_on` it: its inputs (each validated where it is
//! declared, its own base's included, less the keys `except` names) and its outputs with the
//! file that declares them; a chain of bases that comes back to a study is refused.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_saphyr::Spanned;

use crate::definition::case::{parse_located, Loc};
use crate::uq::declaration::{invalid, BasedOn, OutputFile, StudyFile, STUDY_FILE};
use crate::uq::distribution::Input;

/// What a study shares with those based on it: its inputs (each with where it is declared)
/// and its outputs with the file that declares them.
pub(super) struct Shared {
    pub(super) inputs: BTreeMap<String, (Input, Loc)>,
    pub(super) outputs: BTreeMap<String, Spanned<OutputFile>>,
    pub(super) outputs_file: PathBuf,
}

pub(super) fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

/// The inputs and outputs of the study `file` (read from `path`): its base's (less
/// `except`, recursively) and its own. `chain`: the studies on the way here, to refuse a loop.
pub(super) fn shared(
    file: &StudyFile,
    path: &Path,
    chain: &mut Vec<PathBuf>,
) -> Result<Shared, String> {
    let mut inputs = BTreeMap::new();
    let mut base_outputs = None;
    if let Some(b) = &file.based_on {
        let (decl, other) = base_study(b, path, chain)?;
        chain.push(canonical(&other));
        let base = shared(&decl, &other, chain)?;
        inputs = base.inputs;
        for key in &b.value.except {
            if inputs.remove(&key.value).is_none() {
                return Err(invalid(
                    &Loc::of(path, key),
                    "based_on.except",
                    &key.value,
                    &format!("is not an input of {}", other.display()),
                ));
            }
        }
        base_outputs = Some((base.outputs, base.outputs_file));
    }
    for (key, spec) in &file.inputs {
        let loc = Loc::of(path, spec);
        if inputs.contains_key(key) {
            return Err(format!(
                "{loc}: inputs.{key}: also an input of based_on.study: name it in based_on.except to declare it here"
            ));
        }
        let input = crate::uq::distribution::validate(key, spec, path)?;
        inputs.insert(key.clone(), (input, loc));
    }
    let (outputs, outputs_file) = match base_outputs {
        Some(base) if file.outputs.is_empty() => base,
        _ => (file.outputs.clone(), path.to_path_buf()),
    };
    Ok(Shared {
        inputs,
        outputs,
        outputs_file,
    })
}

/// The study `based_on.study`, read and parsed (its file's path beside it); a study already
/// on the chain of bases is refused.
fn base_study(
    b: &Spanned<BasedOn>,
    path: &Path,
    chain: &[PathBuf],
) -> Result<(StudyFile, PathBuf), String> {
    let loc = Loc::of(path, &b.value.study);
    let other = path
        .parent()
        .unwrap_or(Path::new("."))
        .join(&b.value.study.value);
    let text = std::fs::read_to_string(&other).map_err(|e| {
        invalid(
            &loc,
            "based_on.study",
            other.display(),
            &format!("cannot read it: {e}"),
        )
    })?;
    if chain.contains(&canonical(&other)) {
        return Err(invalid(
            &loc,
            "based_on.study",
            other.display(),
            "is already on this chain of bases (a study cannot be based on itself)",
        ));
    }
    parse_located(&text, &other, STUDY_FILE)
        .map(|decl| (decl, other))
        .map_err(|e| e.to_string())
}
