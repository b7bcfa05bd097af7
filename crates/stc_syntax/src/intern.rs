//! Case-insensitive identifier interning.
//!
//! IEC 61131-3 names are case-insensitive. They are folded to upper case once,
//! here, and every later phase compares [`Symbol`]s (a `u32`) instead of
//! strings. The interner remembers the first spelling it saw for display;
//! diagnostics that must show a declaration's own spelling take it from the
//! declaration's span instead.

use rustc_hash::FxHashMap;

/// An interned, case-folded name.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Symbol(pub u32);

#[derive(Default)]
pub struct Interner {
    map: FxHashMap<Box<str>, Symbol>,
    /// Upper-case key of each symbol.
    keys: Vec<Box<str>>,
    /// First spelling seen of each symbol (in the user's text, when the
    /// library's came first).
    spellings: Vec<Box<str>>,
    /// Per symbol: its spelling is the library's, which the first spelling
    /// met in the user's text replaces.
    weak: Vec<bool>,
    /// Interning the library's text (the prelude): its spellings are weak,
    /// so a name shows as the user spells it wherever the prelude is parsed.
    pub library: bool,
    /// The weak spellings replaced, with what they were (for
    /// [`Interner::rewind_spellings`]).
    replaced: Vec<(Symbol, Box<str>)>,
    scratch: String,
}

/// A point in an interner's history of spellings
/// ([`Interner::spelling_mark`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpellingMark {
    symbols: usize,
    replaced: usize,
}

impl Interner {
    pub fn new() -> Interner {
        Interner::default()
    }

    /// Interns a name, case-insensitively.
    pub fn intern(&mut self, name: &str) -> Symbol {
        self.scratch.clear();
        self.scratch
            .extend(name.chars().map(|c| c.to_ascii_uppercase()));
        if let Some(&s) = self.map.get(self.scratch.as_str()) {
            let i = s.0 as usize;
            if self.weak[i] && !self.library {
                let old = std::mem::replace(&mut self.spellings[i], name.into());
                self.replaced.push((s, old));
                self.weak[i] = false;
            }
            return s;
        }
        let s = Symbol(self.keys.len() as u32);
        let key: Box<str> = self.scratch.as_str().into();
        self.map.insert(key.clone(), s);
        self.keys.push(key);
        self.spellings.push(name.into());
        self.weak.push(self.library);
        s
    }

    /// Where the history of spellings is now.
    pub fn spelling_mark(&self) -> SpellingMark {
        SpellingMark {
            symbols: self.keys.len(),
            replaced: self.replaced.len(),
        }
    }

    /// Forgets the spellings given since `m`: the symbols made since are
    /// weak (the next spelling met replaces theirs), and the weak spellings
    /// replaced since are weak again. What the text parsed after `m` spelled
    /// is then spelled by the next text as if it had never been seen (for
    /// a file parsed again: `stc_pipeline::incremental`).
    pub fn rewind_spellings(&mut self, m: SpellingMark) {
        while self.replaced.len() > m.replaced {
            let Some((s, old)) = self.replaced.pop() else {
                break;
            };
            self.spellings[s.0 as usize] = old;
            self.weak[s.0 as usize] = true;
        }
        for w in self.weak.iter_mut().skip(m.symbols) {
            *w = true;
        }
    }

    /// The symbol of a name if it was ever interned.
    pub fn get(&self, name: &str) -> Option<Symbol> {
        let upper = name.to_ascii_uppercase();
        self.map.get(upper.as_str()).copied()
    }

    /// The upper-case form of a symbol.
    pub fn key(&self, s: Symbol) -> &str {
        &self.keys[s.0 as usize]
    }

    /// The first spelling seen of a symbol.
    pub fn spelling(&self, s: Symbol) -> &str {
        &self.spellings[s.0 as usize]
    }

    pub fn len(&self) -> usize {
        self.keys.len()
    }

    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_differing_in_case_are_one_symbol_with_the_first_spelling() {
        let mut i = Interner::new();
        let a = i.intern("Motor_On");
        let b = i.intern("MOTOR_ON");
        let c = i.intern("motor_off");
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_eq!(i.spelling(a), "Motor_On");
        assert_eq!(i.key(a), "MOTOR_ON");
        assert_eq!(i.get("motor_on"), Some(a));
    }

    #[test]
    fn the_users_spelling_replaces_the_librarys_and_can_be_rewound() {
        let mut i = Interner::new();
        i.library = true;
        let a = i.intern("IN");
        i.library = false;
        let m = i.spelling_mark();
        assert_eq!(i.intern("In"), a);
        assert_eq!(i.spelling(a), "In");
        // Only the first spelling of the user's counts.
        i.intern("iN");
        assert_eq!(i.spelling(a), "In");
        let b = i.intern("Speed");
        i.rewind_spellings(m);
        assert_eq!(i.spelling(a), "IN");
        assert_eq!(i.intern("in"), a);
        assert_eq!(i.spelling(a), "in");
        assert_eq!(i.intern("SPEED"), b);
        assert_eq!(i.spelling(b), "SPEED");
    }
}
