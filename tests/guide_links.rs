//! Every relative link of the guide (`docs/guide/src/**/*.md`) and of the
//! README resolves: the file exists (inside the book's `src/`, for the
//! guide, which is all mdBook serves), and an anchor `#id` names a heading
//! of the page it points to, as mdBook makes ids (lower case, spaces to
//! `-`, other punctuation dropped, repeats suffixed `-1`, `-2`, …). Every
//! chapter of `SUMMARY.md` exists and every page is in it. No network:
//! links to other sites are not followed.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Component, Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn book() -> PathBuf {
    root().join("docs/guide/src")
}

/// The page's text outside fenced code blocks and inline code.
fn prose(text: &str) -> String {
    outside(text, false)
}

/// The page's text outside fenced code blocks; inline code dropped, or
/// kept without its backticks (`keep_code`, as a heading's id has it).
fn outside(text: &str, keep_code: bool) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            out.push('\n');
            continue;
        }
        if fenced {
            out.push('\n');
            continue;
        }
        // Inline code spans hold no links.
        let mut in_code = false;
        for ch in line.chars() {
            if ch == '`' {
                in_code = !in_code;
            } else if !in_code || keep_code {
                out.push(ch);
            }
        }
        out.push('\n');
    }
    out
}

/// The targets of `[text](target)` and `![alt](target)` links.
fn links(text: &str) -> Vec<String> {
    let text = prose(text);
    let mut out = Vec::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        if let Some(end) = rest.find(')') {
            let target = rest[..end].split_whitespace().next().unwrap_or("");
            out.push(target.to_string());
            rest = &rest[end..];
        }
    }
    out
}

/// mdBook's heading ids of a page.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = BTreeSet::new();
    for line in outside(text, true).lines() {
        let Some(title) = line.strip_prefix('#') else {
            continue;
        };
        let title = title.trim_start_matches('#').trim();
        let id: String = title
            .chars()
            .filter_map(|c| {
                if c.is_alphanumeric() || c == '_' || c == '-' {
                    Some(c.to_lowercase().next().unwrap_or(c))
                } else if c.is_whitespace() {
                    Some('-')
                } else {
                    None
                }
            })
            .collect();
        let n = seen.entry(id.clone()).or_insert(0);
        out.insert(if *n == 0 {
            id.clone()
        } else {
            format!("{id}-{n}")
        });
        *n += 1;
    }
    out
}

/// `a/b/../c` as `a/c`, without touching the file system.
fn normal(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

fn pages(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("the guide's src/") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            pages(&path, out);
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
}

/// The broken links of `page`; `within`: the folder links must stay in.
fn broken(page: &Path, within: &Path) -> Vec<String> {
    let text = fs::read_to_string(page).expect("a page");
    let mut bad = Vec::new();
    for target in links(&text) {
        if target.is_empty() || target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        let (file, anchor) = match target.split_once('#') {
            Some((f, a)) => (f, Some(a)),
            None => (target.as_str(), None),
        };
        let dest = if file.is_empty() {
            page.to_path_buf()
        } else {
            normal(&page.parent().expect("a folder").join(file))
        };
        if !dest.starts_with(within) {
            bad.push(format!("{target}: leaves {}", within.display()));
            continue;
        }
        if !dest.exists() {
            bad.push(format!("{target}: no such file"));
            continue;
        }
        if let Some(anchor) = anchor {
            let ids = anchors(&fs::read_to_string(&dest).unwrap_or_default());
            if !ids.contains(anchor) {
                bad.push(format!("{target}: no heading with the id `{anchor}`"));
            }
        }
    }
    bad.into_iter()
        .map(|b| format!("{}: {b}", page.display()))
        .collect()
}

#[test]
fn every_link_of_the_guide_and_the_readme_resolves() {
    let mut all = Vec::new();
    pages(&book(), &mut all);
    assert!(all.len() >= 12, "{} pages", all.len());
    let mut bad: Vec<String> = all.iter().flat_map(|p| broken(p, &book())).collect();
    bad.extend(broken(&root().join("README.md"), &root()));
    bad.extend(broken(&root().join("benches/README.md"), &root()));
    assert!(bad.is_empty(), "broken links:\n{}", bad.join("\n"));
}

#[test]
fn every_page_is_in_the_summary() {
    let summary = book().join("SUMMARY.md");
    let listed: BTreeSet<PathBuf> = links(&fs::read_to_string(&summary).expect("SUMMARY.md"))
        .iter()
        .map(|t| normal(&book().join(t)))
        .collect();
    let mut all = Vec::new();
    pages(&book(), &mut all);
    for page in all {
        if page != summary {
            assert!(
                listed.contains(&page),
                "{} is not in SUMMARY.md",
                page.display()
            );
        }
    }
}

#[test]
fn the_checker_finds_a_broken_link_and_a_missing_anchor() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("guide_links");
    fs::create_dir_all(&dir).unwrap();
    fs::write(
        dir.join("b.md"),
        "# A title, with `code`\n\n## Twice\n\n## Twice\n",
    )
    .unwrap();
    let a = dir.join("a.md");
    fs::write(
        &a,
        "[ok](b.md#a-title-with-code) [ok](b.md#twice-1) [ok](https://x.org/y)\n\
         `[not a link](c.md)`\n\
         [bad](c.md) [bad](b.md#nope) [bad](../outside.md)\n",
    )
    .unwrap();
    let bad = broken(&a, &dir);
    assert_eq!(bad.len(), 3, "{bad:?}");
    assert!(bad[0].contains("c.md: no such file"), "{bad:?}");
    assert!(bad[1].contains("no heading with the id `nope`"), "{bad:?}");
    assert!(bad[2].contains("leaves"), "{bad:?}");
}
