//! Typed index vectors: a `Vec` indexed by the id of what it holds
//! (`IdVec<PouId, PouDef>` is indexed by a `PouId`), so an id of one table
//! cannot index another and no caller writes `x.0 as usize`.

use std::fmt;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut, Index, IndexMut};

/// An id that is a position in one table.
pub trait Idx: Copy {
    /// The id of position `i` (tables hold fewer than 2^32 entries).
    fn new(i: usize) -> Self;
    /// Its position.
    fn index(self) -> usize;
}

macro_rules! idx {
    ($($t:ty),*) => {$(
        impl Idx for $t {
            fn new(i: usize) -> Self {
                Self(i as u32)
            }
            fn index(self) -> usize {
                self.0 as usize
            }
        }
    )*};
}

idx!(crate::PouId, crate::VarId, crate::GlobalId, crate::TypeId);

/// A vector indexed by `I`; it derefs to its slice for everything else
/// (`len`, `iter`, `get` by position).
#[derive(Clone, PartialEq, Eq)]
pub struct IdVec<I, T> {
    raw: Vec<T>,
    _id: PhantomData<fn(I) -> I>,
}

impl<I: Idx, T> IdVec<I, T> {
    pub const fn new() -> Self {
        IdVec {
            raw: Vec::new(),
            _id: PhantomData,
        }
    }

    /// Appends `v` and returns its id.
    pub fn push(&mut self, v: T) -> I {
        let i = I::new(self.raw.len());
        self.raw.push(v);
        i
    }

    /// The entry of `i`, if the table has it.
    pub fn get_id(&self, i: I) -> Option<&T> {
        self.raw.get(i.index())
    }

    /// Every entry with its id.
    pub fn iter_enumerated(&self) -> impl Iterator<Item = (I, &T)> {
        self.raw.iter().enumerate().map(|(i, v)| (I::new(i), v))
    }

    /// Every id, in order.
    pub fn ids(&self) -> impl Iterator<Item = I> {
        (0..self.raw.len()).map(I::new)
    }

    pub fn into_raw(self) -> Vec<T> {
        self.raw
    }
}

impl<I: Idx, T> Default for IdVec<I, T> {
    fn default() -> Self {
        IdVec::new()
    }
}

impl<I, T: fmt::Debug> fmt::Debug for IdVec<I, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.raw.fmt(f)
    }
}

impl<I, T> From<Vec<T>> for IdVec<I, T> {
    fn from(raw: Vec<T>) -> Self {
        IdVec {
            raw,
            _id: PhantomData,
        }
    }
}

impl<I, T> FromIterator<T> for IdVec<I, T> {
    fn from_iter<It: IntoIterator<Item = T>>(it: It) -> Self {
        IdVec::from(it.into_iter().collect::<Vec<T>>())
    }
}

impl<I, T> Deref for IdVec<I, T> {
    type Target = Vec<T>;
    fn deref(&self) -> &Vec<T> {
        &self.raw
    }
}

impl<I, T> DerefMut for IdVec<I, T> {
    fn deref_mut(&mut self) -> &mut Vec<T> {
        &mut self.raw
    }
}

impl<I: Idx, T> Index<I> for IdVec<I, T> {
    type Output = T;
    fn index(&self, i: I) -> &T {
        &self.raw[i.index()]
    }
}

impl<I: Idx, T> IndexMut<I> for IdVec<I, T> {
    fn index_mut(&mut self, i: I) -> &mut T {
        &mut self.raw[i.index()]
    }
}

impl<'a, I, T> IntoIterator for &'a IdVec<I, T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.raw.iter()
    }
}

impl<'a, I, T> IntoIterator for &'a mut IdVec<I, T> {
    type Item = &'a mut T;
    type IntoIter = std::slice::IterMut<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.raw.iter_mut()
    }
}

impl<I, T> IntoIterator for IdVec<I, T> {
    type Item = T;
    type IntoIter = std::vec::IntoIter<T>;
    fn into_iter(self) -> Self::IntoIter {
        self.raw.into_iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PouId;

    #[test]
    fn ids_index_and_positions_still_work() {
        let mut v: IdVec<PouId, &str> = IdVec::new();
        let a = v.push("a");
        let b = v.push("b");
        assert_eq!((a, b), (PouId(0), PouId(1)));
        assert_eq!(v[b], "b");
        assert_eq!(v.first(), Some(&"a"));
        v[a] = "z";
        assert_eq!(
            v.iter_enumerated().collect::<Vec<_>>(),
            vec![(PouId(0), &"z"), (PouId(1), &"b")]
        );
        assert_eq!(v.get_id(PouId(2)), None);
    }
}
