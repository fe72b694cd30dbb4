//! The allowed-collision matrix: the pairs never checked (adjacent, rigid, SRDF-disabled, touching).

use std::collections::HashSet;

use super::CollisionModel;
use crate::input::srdf::{SrdfCollisions, SrdfPair};
use crate::model::{JointId, LinkId, Model};

/// Why a pair of links is never checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Allowed {
    /// Joined by a joint (possibly through links without collision geometry).
    Adjacent,
    /// No actuated joint between them: their relative placement never changes.
    Rigid,
    /// Allowed by an SRDF: a `<disable_collisions>` pair, or a `<disable_default_collisions>` link's pair
    /// that no `<enable_collisions>` names.
    Disabled,
    /// In contact at the reference pose (see [`CollisionModel::touching_pairs`]).
    Touching,
}

impl CollisionModel {
    /// Mark adjacent and rigidly attached pairs.
    pub(super) fn allow_structural(&mut self, model: &Model) {
        let adjacent: Vec<(LinkId, LinkId)> = self
            .geometric
            .iter()
            .flat_map(|&link| {
                self.geometric_neighbours(model, link)
                    .into_iter()
                    .map(move |other| (link, other))
            })
            .collect();
        self.allow(&adjacent, Allowed::Adjacent);
        let actuated: Vec<bool> = model.joint_data.iter().map(|j| j.is_actuated()).collect();
        let rigid: Vec<(LinkId, LinkId)> = self
            .geometric_pairs()
            .filter(|&(a, b)| !self.path_has(a, b, |j| actuated.get(j.0).copied().unwrap_or(false)))
            .collect();
        self.allow(&rigid, Allowed::Rigid);
    }

    /// Links with geometry reached from `link` through tree edges, walking through links without geometry
    /// (MoveIt's setup assistant merges such links into their neighbours).
    fn geometric_neighbours(&self, model: &Model, link: LinkId) -> Vec<LinkId> {
        let tree_neighbours = |l: LinkId| {
            let parent = self.parent[l.0].map(|(_, p)| p);
            let children = model.child_joints[l.0]
                .iter()
                .filter_map(|j| model.joint_links[j.0].map(|(_, c)| c));
            parent.into_iter().chain(children)
        };
        let mut seen = vec![link];
        let mut stack: Vec<LinkId> = tree_neighbours(link).collect();
        let mut found = Vec::new();
        while let Some(next) = stack.pop() {
            if seen.contains(&next) {
                continue;
            }
            seen.push(next);
            if self.bodies[next.0].shapes.is_empty() {
                stack.extend(tree_neighbours(next));
            } else {
                found.push(next);
            }
        }
        found
    }

    /// True when a joint on the tree path between `a` and `b` passes `test`.
    pub(super) fn path_has(&self, a: LinkId, b: LinkId, test: impl Fn(JointId) -> bool) -> bool {
        let (mut a, mut b) = (a.0, b.0);
        while a != b {
            let link = if self.depth[a] >= self.depth[b] {
                &mut a
            } else {
                &mut b
            };
            // Two roots: every joint of both paths has been seen.
            let Some((joint, parent)) = self.parent[*link] else {
                return false;
            };
            if test(joint) {
                return true;
            }
            *link = parent.0;
        }
        false
    }

    /// Why `a` and `b` are never checked, if they are not.
    pub fn allowed(&self, a: LinkId, b: LinkId) -> Option<Allowed> {
        let n = self.bodies.len();
        self.allowed.get(a.0 * n + b.0).copied().flatten()
    }

    /// Never check `pairs` again, for `reason` (a pair keeps the first reason it was given). Links out of
    /// range are ignored.
    pub fn allow(&mut self, pairs: &[(LinkId, LinkId)], reason: Allowed) {
        let n = self.bodies.len();
        for &(a, b) in pairs {
            if a.0 < n && b.0 < n {
                for index in [a.0 * n + b.0, b.0 * n + a.0] {
                    self.allowed[index].get_or_insert(reason);
                }
            }
        }
    }

    /// Allow what the SRDF allows (see [`SrdfCollisions`]: `disable_collisions` pairs, and every pair of a
    /// `disable_default_collisions` link but those an `enable_collisions` names); returns one message
    /// per link name the robot does not have (`line:col: ...`), whose entry is otherwise ignored.
    pub fn allow_srdf(&mut self, model: &Model, srdf: &SrdfCollisions) -> Vec<String> {
        let problems = srdf
            .named_links()
            .into_iter()
            .filter(|(_, link, ..)| model.link(link).is_none())
            .map(|(tag, link, line, column)| {
                format!("{line}:{column}: <{tag}> names unknown link '{link}'")
            })
            .collect();
        let known = |pairs: &[SrdfPair]| -> Vec<(LinkId, LinkId)> {
            pairs
                .iter()
                .filter_map(|pair| Some((model.link(&pair.link1)?, model.link(&pair.link2)?)))
                .collect()
        };
        self.allow(&known(&srdf.disabled), Allowed::Disabled);
        // Sets, each entry once: an SRDF is untrusted input and may repeat entries by the thousand.
        let enabled: HashSet<(LinkId, LinkId)> = known(&srdf.enabled)
            .into_iter()
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        let mut by_default_links: Vec<LinkId> = srdf
            .disabled_by_default
            .iter()
            .filter_map(|entry| model.link(&entry.link))
            .collect();
        by_default_links.sort_unstable();
        by_default_links.dedup();
        let by_default: Vec<(LinkId, LinkId)> = by_default_links
            .into_iter()
            .flat_map(|link| self.geometric.iter().map(move |&other| (link, other)))
            .filter(|&(link, other)| {
                link != other && !enabled.contains(&(link.min(other), link.max(other)))
            })
            .collect();
        self.allow(&by_default, Allowed::Disabled);
        problems
    }
}
