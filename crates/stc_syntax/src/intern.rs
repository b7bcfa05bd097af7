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
    /// First spelling seen of each symbol.
    spellings: Vec<Box<str>>,
    scratch: String,
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
            return s;
        }
        let s = Symbol(self.keys.len() as u32);
        let key: Box<str> = self.scratch.as_str().into();
        self.map.insert(key.clone(), s);
        self.keys.push(key);
        self.spellings.push(name.into());
        s
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
}
