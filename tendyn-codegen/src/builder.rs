//! Generation from a build script, in the style of `prost-build`: for firmware that must
//! not run a proc macro, or whose authors want to read the code they ship.
//!
//! ```no_run
//! // In build.rs's `fn main`:
//! tendyn_codegen::Builder::new()
//!     .mechanism("mechanisms/finger.ron")
//!     .outputs(&["generalized_forces", "actuation"])
//!     .scalar(tendyn_codegen::Scalar::F32)
//!     .generate()
//!     .unwrap_or_else(|e| panic!("{e}"));
//! ```
//!
//! and in the crate, `mod finger { tendyn_core::include_mechanism!("finger"); }`.
//!
//! Each mechanism file `dir/stem.ron` becomes `OUT_DIR/stem.rs`. The file is rewritten only
//! when its text changes, so that an unchanged mechanism does not recompile the crate, and
//! cargo is told to rerun the build script when a mechanism file changes.

use crate::{generate_with, Error, Options, Output, Scalar};
use std::path::{Path, PathBuf};

/// Generates the dynamics of one or more mechanism files into `OUT_DIR`.
#[derive(Debug, Clone)]
pub struct Builder {
    mechanisms: Vec<PathBuf>,
    outputs: Option<Vec<String>>,
    scalar: Scalar,
    out_dir: Option<PathBuf>,
    core_path: String,
    emit_rerun_if_changed: bool,
}

impl Default for Builder {
    fn default() -> Self {
        Builder::new()
    }
}

impl Builder {
    /// Every available output, generic over the scalar, reaching `tendyn_core` by that name.
    pub fn new() -> Builder {
        Builder {
            mechanisms: Vec::new(),
            outputs: None,
            scalar: Scalar::Generic,
            out_dir: None,
            core_path: "tendyn_core".to_string(),
            emit_rerun_if_changed: true,
        }
    }

    /// Adds a mechanism file; a relative path is relative to the crate's manifest
    /// directory (where cargo runs build scripts).
    pub fn mechanism(mut self, path: impl AsRef<Path>) -> Builder {
        self.mechanisms.push(path.as_ref().to_path_buf());
        self
    }

    /// The functions to generate, by name (`generalized_forces`, `actuation`,
    /// `mass_matrix`, `bias`, `gravity`, `forward_dynamics`, `segment_tensions`,
    /// `bearings`, `base_reaction`, `generalized_forces_derivatives`,
    /// `forward_dynamics_derivatives`, `actuation_derivatives`, `regressor`). Without this
    /// call, every one of the
    /// first nine the mechanism can provide.
    pub fn outputs<S: AsRef<str>>(mut self, names: &[S]) -> Builder {
        self.outputs = Some(names.iter().map(|s| s.as_ref().to_string()).collect());
        self
    }

    /// `Scalar::F64`, `Scalar::F32`, or `Scalar::Generic` (the default).
    pub fn scalar(mut self, scalar: Scalar) -> Builder {
        self.scalar = scalar;
        self
    }

    /// Where to write; `OUT_DIR` when not set.
    pub fn out_dir(mut self, dir: impl AsRef<Path>) -> Builder {
        self.out_dir = Some(dir.as_ref().to_path_buf());
        self
    }

    /// The path by which generated code reaches `tendyn-core`: `tendyn_core` (the default)
    /// or `::tendyn::core` for a crate that depends on the front crate `tendyn` instead.
    pub fn core_path(mut self, path: &str) -> Builder {
        self.core_path = path.to_string();
        self
    }

    /// Whether to print `cargo:rerun-if-changed` for every mechanism file (default: yes).
    pub fn emit_rerun_if_changed(mut self, on: bool) -> Builder {
        self.emit_rerun_if_changed = on;
        self
    }

    /// Generates every mechanism; returns the files written (or left unchanged).
    pub fn generate(&self) -> Result<Vec<PathBuf>, Error> {
        let out_dir = match &self.out_dir {
            Some(d) => d.clone(),
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or_else(|| {
                    Error::Build(
                        "OUT_DIR is not set: call `out_dir(...)` when not running from a build \
                     script"
                            .to_string(),
                    )
                })?,
        };
        let base = std::env::var_os("CARGO_MANIFEST_DIR").map(PathBuf::from);
        // Every file is generated before any is written: an error leaves the directory as
        // it was.
        let mut sources = Vec::new();
        for path in &self.mechanisms {
            let full = match (&base, path.is_relative()) {
                (Some(b), true) => b.join(path),
                _ => path.clone(),
            };
            if self.emit_rerun_if_changed {
                println!("cargo:rerun-if-changed={}", full.display());
            }
            let shown = path.display().to_string();
            let model = tendyn_core::load(&full).map_err(|e| Error::File {
                path: shown.clone(),
                error: e,
            })?;
            let outputs = self.resolve_outputs(&model)?;
            let stem = full
                .file_stem()
                .and_then(|s| s.to_str())
                .ok_or_else(|| Error::Build(format!("`{shown}` has no file name")))?;
            let options = Options {
                scalar: self.scalar,
                source: file_name(&full),
                core_path: self.core_path.clone(),
            };
            let generated =
                generate_with(&model, &outputs, &options).map_err(|e| Error::Generation {
                    path: shown.clone(),
                    error: Box::new(e),
                })?;
            sources.push((out_dir.join(format!("{stem}.rs")), generated.source()));
        }
        let mut written = Vec::new();
        for (target, source) in sources {
            write_if_changed(&target, &source)?;
            written.push(target);
        }
        Ok(written)
    }

    fn resolve_outputs(&self, model: &tendyn_core::Model<f64>) -> Result<Vec<Output>, Error> {
        match &self.outputs {
            None => Ok(crate::available_outputs(model)),
            Some(names) => names
                .iter()
                .map(|n| Output::parse(n).ok_or_else(|| Error::UnknownOutput(n.clone())))
                .collect(),
        }
    }
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Writes `text` unless the file already holds it, so that its modification time (and
/// with it every dependent compilation) moves only on a real change.
fn write_if_changed(path: &Path, text: &str) -> Result<(), Error> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    write_atomically(path, text)
        .map_err(|e| Error::Build(format!("cannot write {}: {e}", path.display())))
}

/// Writes `text` to `path` whole or not at all: into a temporary file beside it, renamed
/// over `path` once complete, so that a failure part-way (a full disk) never leaves a
/// truncated file for a later build to pick up. The temporary file is removed on failure.
/// A `path` that exists and is not a regular file (a device such as `/dev/null`, a FIFO, a
/// symlink) is written in place instead, so that it stays what it is.
pub fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    // Only a regular file (or none yet) is replaced by a rename. Anything else is written
    // to where it is: a rename over `/dev/null` would make it a regular file that every
    // program then reads its discarded output back from, a rename over a symlink would
    // cut the link, and a FIFO has no contents to protect.
    if let Ok(meta) = std::fs::symlink_metadata(path) {
        if !meta.file_type().is_file() {
            return std::fs::write(path, text);
        }
    }
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let temporary = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let written = std::fs::write(&temporary, text).and_then(|()| std::fs::rename(&temporary, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn writing_to_a_device_or_through_a_symlink_keeps_it_what_it_is() {
        use std::os::unix::fs::FileTypeExt;
        write_atomically(Path::new("/dev/null"), "discarded").unwrap();
        let null = std::fs::metadata("/dev/null").unwrap().file_type();
        assert!(null.is_char_device(), "/dev/null is no longer a device");
        let dir = std::env::temp_dir().join(format!("tendyn-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (file, link) = (dir.join("code.rs"), dir.join("link.rs"));
        std::fs::write(&file, "old").unwrap();
        std::os::unix::fs::symlink(&file, &link).unwrap();
        write_atomically(&link, "new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "new");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn example(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../examples/mechanisms")
            .join(name)
    }

    #[test]
    fn builder_writes_one_file_per_mechanism_named_after_its_stem() {
        let dir = std::env::temp_dir().join(format!("tendyn-builder-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let written = Builder::new()
            .mechanism(example("example1_endless.ron"))
            .outputs(&["generalized_forces"])
            .scalar(Scalar::F64)
            .out_dir(&dir)
            .emit_rerun_if_changed(false)
            .generate()
            .unwrap();
        assert_eq!(written, vec![dir.join("example1_endless.rs")]);
        let text = std::fs::read_to_string(&written[0]).unwrap();
        assert!(text.contains("pub fn generalized_forces(q: &[f64; 2]"));
        assert!(!text.contains("pub fn mass_matrix"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_unchanged_mechanism_leaves_the_generated_file_untouched() {
        let dir = std::env::temp_dir().join(format!("tendyn-builder-mtime-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let build = || {
            Builder::new()
                .mechanism(example("example1_endless.ron"))
                .out_dir(&dir)
                .emit_rerun_if_changed(false)
                .generate()
                .unwrap()
        };
        let path = &build()[0];
        // Mark the file so that a rewrite would show.
        let old = std::fs::metadata(path).unwrap().modified().unwrap();
        let marker = old - std::time::Duration::from_secs(3600);
        let f = std::fs::File::options().write(true).open(path).unwrap();
        f.set_modified(marker).unwrap();
        drop(f);
        build();
        assert_eq!(std::fs::metadata(path).unwrap().modified().unwrap(), marker);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_unknown_output_name_is_refused_with_its_name() {
        let e = Builder::new()
            .mechanism(example("example1_endless.ron"))
            .outputs(&["torques"])
            .out_dir(std::env::temp_dir())
            .emit_rerun_if_changed(false)
            .generate()
            .unwrap_err();
        assert_eq!(e, Error::UnknownOutput("torques".to_string()));
        assert!(e.to_string().contains("generalized_forces"), "{e}");
    }

    #[test]
    fn an_output_one_mechanism_cannot_provide_is_refused_naming_its_file_and_nothing_is_written() {
        let dir = std::env::temp_dir().join(format!("tendyn-builder-gen-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // One link driven by a motor: no tendon, so no segment tensions.
        let motor = dir.join("motor.ron");
        std::fs::write(
            &motor,
            "(name: \"motor1\", links: [(name: \"arm\", dh: (a: 0.2, alpha: 0.0, d: 0.0), \
             mass: 0.5, com: (-0.1, 0.0, 0.0))], motors: [(name: \"m\", on: Joint(\"arm\"))])",
        )
        .unwrap();
        let e = Builder::new()
            .mechanism(example("example1_endless.ron"))
            .mechanism(&motor)
            .outputs(&["segment_tensions"])
            .out_dir(&dir)
            .emit_rerun_if_changed(false)
            .generate()
            .unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("motor.ron") && text.contains("segment_tensions"),
            "{text}"
        );
        // The first mechanism could be generated, but nothing is written.
        assert!(!dir.join("example1_endless.rs").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn asking_for_no_output_is_an_error_naming_the_outputs() {
        let model = tendyn_core::load(example("example1_endless.ron")).unwrap();
        let e = crate::generate(&model, &[], Scalar::Generic, "x.ron").unwrap_err();
        assert_eq!(e, Error::NoOutputs);
        assert!(e.to_string().contains("generalized_forces"), "{e}");
    }

    #[test]
    fn a_bad_mechanism_file_is_refused_with_its_path_and_line() {
        let dir = std::env::temp_dir().join(format!("tendyn-builder-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bad = dir.join("bad.ron");
        std::fs::write(&bad, "(name: \"bad\",\n links: [\n").unwrap();
        let e = Builder::new()
            .mechanism(&bad)
            .out_dir(&dir)
            .emit_rerun_if_changed(false)
            .generate()
            .unwrap_err();
        let text = e.to_string();
        assert!(text.contains("bad.ron") && text.contains("line"), "{text}");
        assert!(!dir.join("bad.rs").exists(), "no output on bad input");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
