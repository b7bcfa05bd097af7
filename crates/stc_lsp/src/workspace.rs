//! The project between edits: the text of every file, the order the files
//! are analysed in, and the last analysis, kept so that an edit re-parses
//! only the file that changed.
//!
//! The files are analysed in URI order, except that the file edited last
//! is moved to the end: its trees are then the last of the project's
//! expression arena and position space, and while the user keeps editing
//! it (the common case: typing in one file), each change cuts the project
//! back to the end of the other files and parses only its new text and the
//! prelude (`stc_pipeline::incremental`). The analysis then runs on the
//! whole tree, so the diagnostics are exactly those of a full analysis of
//! the same files in the same order (`tests::incremental_is_the_full_analysis`).
//! An edit in another file, or a file added, is one full parse in the new
//! order. The order matters only when two files declare the same name: the
//! second declaration in the order is the duplicate (E0105).
//!
//! The analysis is incremental too: what it keeps of the files before the
//! last ([`incremental::Kept`]: the analyser's state after them and their
//! lints' findings) is reused while only the last file changes, so an edit
//! declares and checks only that file (`stc_pipeline::incremental::check`
//! falls back to the whole analysis when the edit could change what the
//! other files mean).

use std::collections::{BTreeMap, BTreeSet};

use stc_pipeline::incremental::{self, Mark};
use stc_pipeline::{Analysed, Options};

use crate::analysis::Project;

pub struct Workspace {
    files: BTreeMap<String, String>,
    /// The order of the last analysis: the file edited last is last.
    order: Vec<String>,
    /// Files whose text changed since the last analysis.
    dirty: BTreeSet<String>,
    /// Where the files before the last one end in the last analysis.
    mark: Option<Mark>,
    /// What the last analysis kept of the files before the last one.
    kept: Option<incremental::Kept>,
    project: Option<Project>,
    /// The last analysis, until [`Workspace::finish`] lowers it.
    pending: Option<stc_pipeline::Pending>,
    /// The previous lowered module and the analysis that was not lowered,
    /// freed in [`Workspace::finish`] (so freeing them is not on the way to
    /// the diagnostics).
    old_module: Option<stc_pipeline::Module>,
    stale: Option<stc_pipeline::Pending>,
    opts: Options,
    lints: Option<stc_lint::Levels>,
    /// Whether the last analysis parsed only the last file.
    pub last_was_incremental: bool,
    /// Whether the last analysis declared and checked only the last file.
    pub last_was_resumed: bool,
}

impl Workspace {
    /// A workspace of files (URI, text), analysed with the lints at
    /// `lints` (none with `None`).
    pub fn new(
        files: Vec<(String, String)>,
        opts: Options,
        lints: Option<stc_lint::Levels>,
    ) -> Workspace {
        let files: BTreeMap<String, String> = files.into_iter().collect();
        Workspace {
            dirty: files.keys().cloned().collect(),
            files,
            order: Vec::new(),
            mark: None,
            kept: None,
            project: None,
            pending: None,
            old_module: None,
            stale: None,
            opts,
            lints,
            last_was_incremental: false,
            last_was_resumed: false,
        }
    }

    /// Sets the text of a file (a new file is added).
    pub fn set(&mut self, uri: String, text: String) {
        if self.files.get(&uri) != Some(&text) {
            self.dirty.insert(uri.clone());
            self.files.insert(uri, text);
        }
    }

    pub fn text(&self, uri: &str) -> Option<&str> {
        self.files.get(uri).map(String::as_str)
    }

    pub fn uris(&self) -> impl Iterator<Item = &String> {
        self.files.keys()
    }

    /// The order of the last analysis.
    pub fn order(&self) -> &[String] {
        &self.order
    }

    pub fn project(&self) -> Option<&Project> {
        self.project.as_ref()
    }

    /// Analyses the project if a file changed since the last analysis (up
    /// to the lints: [`Workspace::finish`] does the rest).
    pub fn analyse(&mut self) {
        if self.dirty.is_empty() && self.project.is_some() {
            return;
        }
        let dirty = std::mem::take(&mut self.dirty);
        let same_files = self.order.len() == self.files.len()
            && self.order.iter().all(|u| self.files.contains_key(u));
        let last = self.order.last().cloned();
        let opts = self.opts;
        let lints = self.lints;
        // The analysis waiting to be lowered is out of date: freed later.
        let stale = self.pending.take();
        if let (true, Some(last), Some(mark), true) = (
            same_files,
            last.clone(),
            self.mark,
            dirty.len() == 1 && dirty.first() == self.order.last(),
        ) {
            if let Some(old) = self.project.take() {
                let text = self.files.get(&last).cloned().unwrap_or_default();
                let kept = self.kept.take();
                let (analysed, pending, kept, made, module) =
                    stc_pipeline::with_big_stack(move || {
                        let Analysed { parsed, module, .. } = old.into_analysed();
                        let parsed = incremental::reparse_last(parsed, mark, last, text, &opts);
                        let (a, p, k, m) =
                            incremental::check(parsed, mark, &opts, lints.as_ref(), kept);
                        (a, p, k, m, module)
                    });
                self.project = Some(Project::from_analysed(analysed));
                self.pending = Some(pending);
                self.kept = kept;
                self.old_module = self.old_module.take().or(module);
                self.last_was_incremental = true;
                self.last_was_resumed = made == incremental::Made::Resumed;
                // Freed here only when nothing else is to do.
                self.stale = stale;
                return;
            }
        }
        let mut order: Vec<String> = self.files.keys().cloned().collect();
        let to_end = if dirty.len() == 1 {
            dirty.first().cloned()
        } else {
            last.filter(|l| self.files.contains_key(l))
        };
        if let Some(e) = to_end {
            order.retain(|u| *u != e);
            order.push(e);
        }
        let files: Vec<(String, String)> = order
            .iter()
            .map(|u| (u.clone(), self.files.get(u).cloned().unwrap_or_default()))
            .collect();
        // The old analysis is dropped before the new one is made (the
        // memory of two large projects at once is not needed).
        self.project = None;
        self.old_module = None;
        self.kept = None;
        drop(stale);
        let (analysed, pending, mark, kept, made) = stc_pipeline::with_big_stack(move || {
            let (parsed, mark) = incremental::parse_all(files, &opts);
            let (a, p, k, m) = incremental::check(parsed, mark, &opts, lints.as_ref(), None);
            (a, p, mark, k, m)
        });
        self.project = Some(Project::from_analysed(analysed));
        self.pending = Some(pending);
        self.mark = Some(mark);
        self.kept = kept;
        self.order = order;
        self.last_was_incremental = false;
        self.last_was_resumed = made == incremental::Made::Resumed;
    }

    /// Whether [`Workspace::finish`] has something to do.
    pub fn has_work(&self) -> bool {
        self.pending.is_some() || self.old_module.is_some() || self.stale.is_some()
    }

    /// The rest of the last analysis: without errors, the project is
    /// lowered and its memory layout checked (E0901); what is out of date
    /// is freed. Returns whether the diagnostics changed. A server calls it
    /// after publishing the analysis's diagnostics, when no message came
    /// for a while.
    pub fn finish(&mut self) -> bool {
        self.old_module = None;
        self.stale = None;
        let (Some(pending), Some(project)) = (self.pending.take(), self.project.as_mut()) else {
            return false;
        };
        let analysed = project.analysed_mut();
        stc_pipeline::with_big_stack(move || stc_pipeline::lay_out(analysed, pending))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The diagnostics of every file, sorted, as the editor sees them.
    fn diagnostics(p: &Project) -> Vec<(String, String)> {
        let mut out: Vec<(String, String)> = p
            .diagnostics_by_uri()
            .into_iter()
            .flat_map(|(u, ds)| {
                ds.into_iter()
                    .map(move |d| (u.clone(), serde_json::to_string(&d).unwrap_or_default()))
            })
            .collect();
        out.sort();
        out
    }

    const LIB: &str = "TYPE Mode : (Off, Auto); END_TYPE\n\
        VAR_GLOBAL g : INT; END_VAR\n\
        FUNCTION_BLOCK Counter\nVAR_INPUT pulse : BOOL; END_VAR\nVAR_OUTPUT count : INT; END_VAR\n\
        IF pulse THEN count := count + 1; END_IF;\nEND_FUNCTION_BLOCK\n\
        FUNCTION Twice : INT\nVAR_INPUT x : INT; END_VAR\nTwice := x * 2;\nEND_FUNCTION\n";

    #[test]
    fn incremental_is_the_full_analysis() {
        let main = |body: &str| {
            format!(
                "PROGRAM Main\nVAR c : Counter; level : INT; m : Mode; r : REAL; END_VAR\n{body}\nEND_PROGRAM\n"
            )
        };
        // A sequence of edits of one file: valid, half-typed, type errors,
        // a name that another file declares too, lints, back to valid.
        let edits = [
            main("c(pulse := TRUE);\nlevel := c.count;"),
            main("c(pulse := TRUE);\nlevel := c.count + ;"),
            main("c(pulse := TRUE);\nlevel := 'text';"),
            main("level := c.count;\nc(pulse := TRUE);\nm := Auto;"),
            main("IF r = 1.0 THEN level := Twice(level); END_IF;\nc(pulse := level > 3);"),
            "FUNCTION Twice : INT\nVAR_INPUT y : INT; END_VAR\nTwice := 2;\nEND_FUNCTION\n".into(),
            main("c(pulse := TRUE);\nlevel := c.count;\ng := level;"),
            main("c(pulse := TRUE);\nlevel := c.count;"),
        ];
        let lints = Some(stc_lint::Levels::all(stc_lint::Level::Warn));
        let mut ws = Workspace::new(
            vec![
                ("file:///lib.st".into(), LIB.into()),
                ("file:///main.st".into(), edits[0].clone()),
            ],
            Options::default(),
            lints,
        );
        ws.analyse();
        let mut incremental = 0;
        let mut resumed = 0;
        for (i, text) in edits.iter().enumerate() {
            ws.set("file:///main.st".into(), text.clone());
            ws.analyse();
            ws.finish();
            incremental += usize::from(ws.last_was_incremental);
            resumed += usize::from(ws.last_was_resumed);
            let files: Vec<(String, String)> = ws
                .order()
                .iter()
                .map(|u| (u.clone(), ws.text(u).unwrap_or_default().to_string()))
                .collect();
            let full = Project::analyse_with(files, Options::default(), lints);
            let got = diagnostics(ws.project().expect("analysed"));
            assert_eq!(got, diagnostics(&full), "edit {i}");
        }
        assert!(incremental >= edits.len() - 1, "{incremental}");
        // Declaring `Twice` again reaches the other file (its duplicate);
        // every other edit is analysed from what the last one kept.
        assert!(resumed >= edits.len() - 2, "{resumed}");
        // An edit of the other file is a full analysis in a new order.
        ws.set("file:///lib.st".into(), format!("{LIB}\n"));
        ws.analyse();
        assert!(!ws.last_was_incremental);
        assert_eq!(
            ws.order().last().map(String::as_str),
            Some("file:///lib.st")
        );
    }
}
