//! The file list and every error a user's folder can give, on folders made
//! for each test under the system's temporary directory.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use super::*;
use crate::report::Located;

/// A model that is accepted: the checkout's `coulomb`, under any name.
const COULOMB: &str = include_str!("../../../models/coulomb.ssm");

fn model(name: &str) -> String {
    COULOMB.replacen("model coulomb {", &format!("model {name} {{"), 1)
}

/// A fresh folder, removed when dropped.
struct Temp(PathBuf);

impl Temp {
    fn new() -> Temp {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("stickslip-model-files-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create a temporary folder");
        Temp(dir)
    }

    /// A sub-folder `name` holding `files` (`(file name, content)`).
    fn folder(&self, name: &str, files: &[(&str, &[u8])]) -> PathBuf {
        let dir = self.0.join(name);
        std::fs::create_dir_all(&dir).expect("create a folder");
        for (file, content) in files {
            std::fs::write(dir.join(file), content).expect("write a file");
        }
        dir
    }
}

impl Drop for Temp {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn var(folders: &[&Path]) -> OsString {
    std::env::join_paths(folders).expect("folders without the separator")
}

fn origin(dir: &Path, file: &str) -> String {
    dir.join(file).display().to_string()
}

/// The one error of `report`, as `(message, Some((line, col)))`.
fn only(report: &Report) -> (&str, Option<(usize, usize)>) {
    assert_eq!(report.errors.len(), 1, "{}", report.render());
    let e: &Located = &report.errors[0];
    (&e.message, e.position.map(|p| (p.line, p.column)))
}

/// Line and column (from 1) of the first occurrence of `needle` in `text`,
/// found by scanning the text (independently of the tokenizer's spans).
fn find(text: &str, needle: &str) -> (usize, usize) {
    for (i, line) in text.lines().enumerate() {
        if let Some(byte) = line.find(needle) {
            return (i + 1, line[..byte].chars().count() + 1);
        }
    }
    panic!("`{needle}` is not in the text");
}

#[test]
fn built_in_then_each_user_folder_in_order_by_name() {
    let t = Temp::new();
    let models = t.folder(
        "models",
        &[
            ("b.ssm", b"x"),
            ("a.ssm", b"x"),
            ("README.md", b"x"),
            (".#a.ssm", b"x"),
        ],
    );
    let one = t.folder("one", &[("z.ssm", b"x")]);
    let two = t.folder("two", &[("d.ssm", b"x"), ("c.ssm", b"x")]);
    // An empty entry (`::`) is ignored, as an unset variable is.
    let user = var(&[&two, Path::new(""), &one]);
    let files = list(&models, "models", Some(&user), &t.0);
    assert!(files.errors.is_empty(), "{:?}", files.errors);
    let got: Vec<(&str, bool)> = files
        .files
        .iter()
        .map(|f| (f.origin.as_str(), f.built_in))
        .collect();
    let (c, d, z) = (
        origin(&two, "c.ssm"),
        origin(&two, "d.ssm"),
        origin(&one, "z.ssm"),
    );
    assert_eq!(
        got,
        vec![
            ("models/a.ssm", true),
            ("models/b.ssm", true),
            (c.as_str(), false),
            (d.as_str(), false),
            (z.as_str(), false),
        ]
    );
    assert_eq!(files.files[2].stem, "c");
    assert_eq!(files.files[2].path, two.join("c.ssm"));
    // Every folder and every file is watched.
    let watched: Vec<&Path> = files.watched().collect();
    for p in [&models, &two, &one] {
        assert!(watched.contains(&p.as_path()), "{p:?} not watched");
    }
    for f in &files.files {
        assert!(
            watched.contains(&f.path.as_path()),
            "{:?} not watched",
            f.path
        );
    }
    // Unset or empty: the built-in models alone.
    for user in [None, Some(OsString::new())] {
        let files = list(&models, "models", user.as_deref(), &t.0);
        assert_eq!(files.files.len(), 2);
        assert!(files.errors.is_empty());
    }
}

#[test]
fn a_relative_folder_is_read_from_base_and_named_as_given() {
    let t = Temp::new();
    let models = t.folder("models", &[("a.ssm", b"x")]);
    t.folder("mine", &[("s.ssm", b"x")]);
    let files = list(&models, "models", Some(OsStr::new("mine")), &t.0);
    assert!(files.errors.is_empty());
    assert_eq!(
        files.files[1].origin,
        format!("mine{}s.ssm", std::path::MAIN_SEPARATOR)
    );
    assert_eq!(files.files[1].path, t.0.join("mine").join("s.ssm"));
}

#[test]
fn a_folder_given_twice_or_the_built_in_folder_is_read_once() {
    let t = Temp::new();
    let models = t.folder("models", &[("a.ssm", model("a").as_bytes())]);
    let mine = t.folder("mine", &[("s.ssm", model("s").as_bytes())]);
    let again = t.0.join("mine").join("..").join("mine");
    let files = list(
        &models,
        "models",
        Some(&var(&[&mine, &again, &models])),
        &t.0,
    );
    assert!(files.errors.is_empty(), "{:?}", files.errors);
    assert_eq!(files.files.len(), 2);
    let generated = generate(&files).expect("no clash with itself");
    let names: Vec<&str> = generated.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["a", "s"]);
}

#[test]
fn a_missing_folder_is_an_error_naming_it() {
    let t = Temp::new();
    let models = t.folder("models", &[("a.ssm", b"x")]);
    let gone = t.0.join("gone");
    let files = list(&models, "models", Some(gone.as_os_str()), &t.0);
    assert_eq!(files.errors.len(), 1);
    let (message, at) = only(&files.errors[0]);
    assert_eq!(at, None);
    assert_eq!(
        message,
        format!(
            "STICKSLIP_MODELS: the folder `{}` does not exist",
            gone.display()
        )
    );
    // Relative: where it was looked for is said.
    let files = list(&models, "models", Some(OsStr::new("gone")), &t.0);
    let (message, _) = only(&files.errors[0]);
    assert_eq!(
        message,
        format!(
            "STICKSLIP_MODELS: the folder `gone` (read as {}) does not exist",
            gone.display()
        )
    );
    // The missing folder is still watched: creating it builds again.
    assert!(files.watched().any(|p| p == gone));
    assert!(generate(&files).is_err());
}

#[test]
fn a_file_given_as_a_folder_is_an_error() {
    let t = Temp::new();
    let models = t.folder("models", &[("a.ssm", b"x")]);
    let mine = t.folder("mine", &[("s.ssm", b"x")]);
    let file = mine.join("s.ssm");
    let files = list(&models, "models", Some(file.as_os_str()), &t.0);
    let (message, _) = only(&files.errors[0]);
    assert!(
        message.starts_with(&format!(
            "STICKSLIP_MODELS: the folder `{}` is a file, not a folder",
            file.display()
        )),
        "{message}"
    );
    assert_eq!(files.files.len(), 1, "the built-in model alone");
}

#[test]
fn a_folder_without_model_files_is_an_error_saying_what_it_holds() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    let empty = t.folder("empty", &[]);
    let other = t.folder(
        "other",
        &[
            ("spring.SSM", b"x"),
            ("b.txt", b"x"),
            ("a.rs", b"x"),
            ("c", b"x"),
            (".hidden.ssm", b"x"),
        ],
    );
    let files = list(&models, "models", Some(&var(&[&empty, &other])), &t.0);
    assert_eq!(files.errors.len(), 2);
    let (message, _) = only(&files.errors[0]);
    assert_eq!(
        message,
        format!(
            "STICKSLIP_MODELS: the folder `{}` holds no model file `*.ssm`: it is empty",
            empty.display()
        )
    );
    let (message, _) = only(&files.errors[1]);
    assert_eq!(
        message,
        format!(
            "STICKSLIP_MODELS: the folder `{}` holds no model file `*.ssm`: it holds 4 \
             other entries (`a.rs`, `b.txt`, `c`, ...)",
            other.display()
        )
    );
    let errors = generate(&files).expect_err("nothing silently built");
    assert_eq!(errors.len(), 2);
    let text = render(&errors, &files);
    assert!(
        text.contains(&format!("1 error in {}\n", empty.display())),
        "{text}"
    );
    assert!(text.ends_with(&format!(
        "stickslip: invalid model file(s) in {}, {}, {}\n",
        models.display(),
        empty.display(),
        other.display()
    )));
}

#[test]
fn a_user_model_named_like_a_built_in_one_is_an_error_at_its_name() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    // Two lines more above the name than the built-in file has.
    let text = format!("// mine\n\n{COULOMB}");
    let mine = t.folder("mine", &[("coulomb.ssm", text.as_bytes())]);
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    let errors = generate(&files).expect_err("a clash");
    assert_eq!(errors.len(), 1);
    assert_eq!(errors[0].file, origin(&mine, "coulomb.ssm"));
    let (message, at) = only(&errors[0]);
    assert_eq!(
        message,
        "a model named `coulomb` is already compiled in: a built-in model, in \
         models/coulomb.ssm; rename this model and its file"
    );
    let (line, col) = find(&text, "model coulomb");
    assert_eq!(at, Some((line, col + "model ".len())));
    let rendered = errors[0].render();
    assert!(
        rendered.contains(&format!(
            "--> {}:{line}:{}",
            origin(&mine, "coulomb.ssm"),
            col + 6
        )),
        "{rendered}"
    );
}

#[test]
fn two_user_models_of_one_name_clash_at_the_later_one() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    let one = t.folder("one", &[("spring.ssm", model("spring").as_bytes())]);
    let two = t.folder("two", &[("spring.ssm", model("spring").as_bytes())]);
    let files = list(&models, "models", Some(&var(&[&one, &two])), &t.0);
    let errors = generate(&files).expect_err("a clash");
    assert_eq!(errors.len(), 1);
    assert_eq!(errors[0].file, origin(&two, "spring.ssm"));
    let (message, at) = only(&errors[0]);
    assert_eq!(
        message,
        format!(
            "a model named `spring` is already compiled in: another model, in {}; \
             rename this model and its file",
            origin(&one, "spring.ssm")
        )
    );
    let (line, col) = find(&model("spring"), "model spring");
    assert_eq!(at, Some((line, col + 6)));
}

#[test]
fn names_differing_only_in_case_clash() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    let mine = t.folder("mine", &[("Coulomb.ssm", model("Coulomb").as_bytes())]);
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    let errors = generate(&files).expect_err("a clash");
    let (message, at) = only(&errors[0]);
    assert!(
        message.starts_with(
            "the model `Coulomb` differs only in case from `coulomb`, a built-in model, \
             in models/coulomb.ssm"
        ),
        "{message}"
    );
    assert!(at.is_some());
}

#[test]
fn a_clashing_file_that_does_not_parse_gets_its_errors_and_the_clash() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    let mine = t.folder("mine", &[("coulomb.ssm", b"model {")]);
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    let errors = generate(&files).expect_err("errors");
    assert_eq!(errors.len(), 1, "one report for the file");
    let report = &errors[0];
    assert!(report.errors.len() >= 2);
    let last = report.errors.last().expect("the clash");
    assert!(last.message.starts_with("a model named `coulomb`"));
    assert_eq!(last.position, None);
}

#[test]
fn errors_of_a_user_model_are_located_in_the_user_file() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    // The model is not named like its file.
    let text = model("other");
    let mine = t.folder("mine", &[("spring.ssm", text.as_bytes())]);
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    let errors = generate(&files).expect_err("a misnamed model");
    assert_eq!(errors.len(), 1);
    let (message, at) = only(&errors[0]);
    assert!(
        message.starts_with("the model is named `other`"),
        "{message}"
    );
    let (line, col) = find(&text, "model other");
    assert_eq!(at, Some((line, col + 6)));
    let rendered = render(&errors, &files);
    let user = origin(&mine, "spring.ssm");
    assert!(
        rendered.contains(&format!("--> {user}:{line}:{}", col + 6)),
        "{rendered}"
    );
}

#[test]
fn a_user_file_that_is_not_utf8_is_located_at_the_bad_byte() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    let mut bytes = model("spring").into_bytes();
    // Line 3, after four characters.
    let line3 = bytes
        .iter()
        .enumerate()
        .filter(|(_, &b)| b == b'\n')
        .nth(1)
        .map(|(i, _)| i + 1)
        .expect("three lines");
    bytes[line3 + 4] = 0xFF;
    let mine = t.folder("mine", &[("spring.ssm", &bytes)]);
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    let errors = generate(&files).expect_err("not UTF-8");
    assert_eq!(errors[0].file, origin(&mine, "spring.ssm"));
    let (message, at) = only(&errors[0]);
    assert!(
        message.contains("not valid UTF-8 at byte 0xFF"),
        "{message}"
    );
    assert_eq!(at, Some((3, 5)));
}

#[test]
fn an_unreadable_user_file_is_an_error_naming_it() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    // A folder named like a model file cannot be read as one, by anyone
    // (permissions do not stop root).
    let mine = t.folder("mine", &[]);
    std::fs::create_dir(mine.join("spring.ssm")).expect("a folder");
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    assert!(files.errors.is_empty());
    let errors = generate(&files).expect_err("unreadable");
    let (message, at) = only(&errors[0]);
    assert_eq!(errors[0].file, origin(&mine, "spring.ssm"));
    assert!(
        message.starts_with(&format!(
            "cannot read {}",
            mine.join("spring.ssm").display()
        )),
        "{message}"
    );
    assert_eq!(at, None);
}

#[cfg(unix)]
#[test]
fn a_file_name_that_is_not_utf8_is_an_error() {
    use std::os::unix::ffi::OsStrExt;
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    let mine = t.folder("mine", &[]);
    let name = OsStr::from_bytes(b"spr\xFFing.ssm");
    if std::fs::write(mine.join(name), b"x").is_err() {
        return; // a file system that refuses such names cannot hold one
    }
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    assert_eq!(files.errors.len(), 1);
    let (message, _) = only(&files.errors[0]);
    assert!(message.contains("is not UTF-8"), "{message}");
    assert!(message.contains("spr\u{FFFD}ing.ssm"), "{message}");
}

#[test]
fn user_models_are_generated_after_the_built_in_ones() {
    let t = Temp::new();
    let models = t.folder("models", &[("coulomb.ssm", COULOMB.as_bytes())]);
    let mine = t.folder("mine", &[("spring.ssm", model("spring").as_bytes())]);
    let files = list(&models, "models", Some(mine.as_os_str()), &t.0);
    let generated = generate(&files).expect("valid");
    let names: Vec<&str> = generated.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["coulomb", "spring"]);
    // The generated code names the user's file, as given, as its origin.
    assert!(
        generated[1].code.contains(&origin(&mine, "spring.ssm")),
        "{}",
        &generated[1].code[..400]
    );
}
