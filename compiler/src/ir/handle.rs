//! Typed handles into arenas.

use std::fmt;
use std::marker::PhantomData;
use std::num::NonZeroU32;

/// The name of a `T` in an [`Arena<T>`]: its index plus one, so that an
/// `Option<Handle<T>>` costs no more than the handle.
pub struct Handle<T> {
    index: NonZeroU32,
    _of: PhantomData<fn() -> T>,
}

impl<T> Handle<T> {
    /// The handle of the `i`-th item (0-based); `None` past `u32::MAX - 1`.
    pub fn from_index(i: usize) -> Option<Handle<T>> {
        let n = u32::try_from(i).ok()?.checked_add(1)?;
        Some(Handle {
            index: NonZeroU32::new(n)?,
            _of: PhantomData,
        })
    }

    /// The 0-based index.
    pub fn index(self) -> usize {
        (self.index.get() - 1) as usize
    }
}

impl<T> Clone for Handle<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Handle<T> {}
impl<T> PartialEq for Handle<T> {
    fn eq(&self, other: &Self) -> bool {
        self.index == other.index
    }
}
impl<T> Eq for Handle<T> {}
impl<T> PartialOrd for Handle<T> {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl<T> Ord for Handle<T> {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.index.cmp(&other.index)
    }
}
impl<T> std::hash::Hash for Handle<T> {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.index.hash(state)
    }
}
impl<T> fmt::Debug for Handle<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.index())
    }
}

/// A growing vector of `T` named by handles.
#[derive(Debug)]
pub struct Arena<T> {
    items: Vec<T>,
}

impl<T> Default for Arena<T> {
    fn default() -> Self {
        Arena { items: Vec::new() }
    }
}

impl<T> Arena<T> {
    pub fn with_capacity(n: usize) -> Arena<T> {
        Arena {
            items: Vec::with_capacity(n),
        }
    }

    /// Adds an item. An arena is never this large: a program of more than
    /// four billion items could not have been read into memory.
    pub fn append(&mut self, item: T) -> Handle<T> {
        let h = Handle::from_index(self.items.len());
        self.items.push(item);
        match h {
            Some(h) => h,
            None => unreachable!("an arena of more than u32::MAX - 1 items"),
        }
    }

    pub fn get(&self, h: Handle<T>) -> Option<&T> {
        self.items.get(h.index())
    }

    pub fn get_mut(&mut self, h: Handle<T>) -> Option<&mut T> {
        self.items.get_mut(h.index())
    }

    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// The items with their handles, in the order they were added.
    pub fn iter(&self) -> impl Iterator<Item = (Handle<T>, &T)> {
        self.items
            .iter()
            .enumerate()
            .filter_map(|(i, t)| Some((Handle::from_index(i)?, t)))
    }

    /// Every item, mutable, in order (a pass that rewrites items where
    /// they are).
    pub fn items_mut(&mut self) -> impl Iterator<Item = &mut T> {
        self.items.iter_mut()
    }

    /// Whether `h` names an item of this arena.
    pub fn contains(&self, h: Handle<T>) -> bool {
        h.index() < self.items.len()
    }
}

impl<T> std::ops::Index<Handle<T>> for Arena<T> {
    type Output = T;
    fn index(&self, h: Handle<T>) -> &T {
        &self.items[h.index()]
    }
}

#[cfg(test)]
mod tests {
    use super::{Arena, Handle};

    #[test]
    fn handles_name_their_items_and_cost_no_more_as_options() {
        let mut a = Arena::default();
        let x = a.append('x');
        let y = a.append('y');
        assert_eq!((x.index(), y.index(), a[y]), (0, 1, 'y'));
        assert!(a.contains(y) && !a.contains(Handle::from_index(2).unwrap()));
        // The last index a u32 can name (plus one) is u32::MAX - 1.
        assert!(Handle::<char>::from_index(u32::MAX as usize - 1).is_some());
        assert!(Handle::<char>::from_index(u32::MAX as usize).is_none());
        assert_eq!(std::mem::size_of::<Option<Handle<char>>>(), 4);
    }
}
