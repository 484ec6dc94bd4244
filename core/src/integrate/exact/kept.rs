//! The last few things a run has built and may need again (the energy books' quadratic forms,
//! a record's recurrences): kept in a ring, the one that served last tried first.

/// The last `N` items built, at most.
#[derive(Debug)]
pub(crate) struct Kept<T, const N: usize> {
    items: Vec<T>,
    /// The slot the next new item takes once every slot is in use.
    next: usize,
    /// The slot that served last (tried first: consecutive flows mostly share their items).
    last: usize,
    /// Items built so far: a slot keeps its item while this stays the same.
    builds: usize,
}

impl<T, const N: usize> Default for Kept<T, N> {
    fn default() -> Self {
        Kept {
            items: Vec::new(),
            next: 0,
            last: 0,
            builds: 0,
        }
    }
}

impl<T, const N: usize> Kept<T, N> {
    /// The kept item for which `serves` holds; else the one `build` makes, kept in place of the
    /// oldest once N are kept; None where there is none and `build` makes none.
    pub fn serve(
        &mut self,
        serves: impl Fn(&T) -> bool,
        build: impl FnOnce() -> Option<T>,
    ) -> Option<&T> {
        let found = if self.items.get(self.last).is_some_and(&serves) {
            Some(self.last)
        } else {
            self.items.iter().position(&serves)
        };
        let slot = match found {
            Some(slot) => slot,
            None => {
                let built = build()?;
                self.builds += 1;
                if self.items.len() < N {
                    self.items.push(built);
                    self.items.len() - 1
                } else {
                    let slot = self.next;
                    self.items[slot] = built;
                    self.next = (slot + 1) % N;
                    slot
                }
            }
        };
        self.last = slot;
        Some(&self.items[slot])
    }

    /// The slot that served last, and the number of items built so far: a handle on that item,
    /// valid while no other is built ([`Kept::get`]).
    pub fn last(&self) -> (usize, usize) {
        (self.last, self.builds)
    }

    /// The item in `slot`, if `builds` items have been built (none has taken its place since
    /// [`Kept::last`] gave the handle).
    pub fn get(&self, (slot, builds): (usize, usize)) -> Option<&T> {
        (builds == self.builds)
            .then(|| self.items.get(slot))
            .flatten()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_oldest_item_makes_room_and_a_kept_one_is_not_built_again() {
        let mut kept: Kept<u32, 2> = Kept::default();
        let mut built = Vec::new();
        let mut serve = |kept: &mut Kept<u32, 2>, wanted: u32| {
            *kept
                .serve(
                    |&item| item == wanted,
                    || {
                        built.push(wanted);
                        Some(wanted)
                    },
                )
                .unwrap()
        };
        for wanted in [1, 2, 1, 3, 2, 1] {
            assert_eq!(serve(&mut kept, wanted), wanted);
        }
        assert!(kept.serve(|&item| item == 9, || None).is_none());
        // A handle names the item that served last until another is built (2 again, in 3's
        // slot; 1 is still kept; 4 is built).
        serve(&mut kept, 2);
        let handle = kept.last();
        assert_eq!(kept.get(handle), Some(&2));
        serve(&mut kept, 1);
        assert_eq!(kept.get(handle), Some(&2));
        serve(&mut kept, 4);
        assert_eq!(kept.get(handle), None);
        // 1 and 2 are built, served again; 3 takes 1's slot, 2 is still kept, 1 is built again.
        assert_eq!(built, [1, 2, 3, 1, 2, 4]);
    }
}
