//! The frame graph of a [`Scene`]: every frame's pose in the model frame (following `relative_to`), and
//! the link each frame is attached to (following `attached_to`, a joint's child, a model's canonical
//! link). Cycles and names that do not exist are findings, never a loop or a panic.

use std::collections::{HashMap, HashSet};

use super::pose::Transform;
use super::scene::{Kind, Ref, Scene};
use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::span::Span;
use crate::diagnostics::suggest::did_you_mean;

/// Resolves poses and attachments of one scene, memoising them.
pub struct FrameGraph<'s, 'a> {
    scene: &'s Scene<'a>,
    poses: HashMap<String, Option<Transform>>,
    links: HashMap<String, Option<String>>,
    reported: HashSet<(Span, &'static str)>,
    /// Findings: cycles and undefined names, once each.
    pub findings: Vec<Finding>,
}

impl<'s, 'a> FrameGraph<'s, 'a> {
    /// The graph of `scene`.
    pub fn new(scene: &'s Scene<'a>) -> Self {
        FrameGraph {
            scene,
            poses: HashMap::new(),
            links: HashMap::new(),
            reported: HashSet::new(),
            findings: Vec::new(),
        }
    }

    fn report(&mut self, rule: &'static rules::Rule, span: Span, message: String) {
        if self.reported.insert((span, rule.code)) {
            self.findings.push(Finding::new(rule, span, message));
        }
    }

    /// Whether `name` is a frame of the scene (the model frame `""` and `world` are).
    pub fn exists(&self, name: &str) -> bool {
        name.is_empty() || name == "world" || self.scene.frames.contains_key(name)
    }

    /// The frame `reference` names, or its fallback (the enclosing model frame) with a U023 finding.
    pub fn target(&mut self, reference: &Ref) -> String {
        if self.exists(&reference.name) {
            return reference.name.clone();
        }
        // Once per reference: the suggestion scans every frame name.
        if self
            .reported
            .contains(&(reference.span, rules::SDF_UNDEFINED_FRAME.code))
        {
            return reference.fallback.clone();
        }
        let help = did_you_mean(
            &reference.name,
            self.scene.frames.keys().map(String::as_str),
        );
        self.reported
            .insert((reference.span, rules::SDF_UNDEFINED_FRAME.code));
        self.findings.push(
            Finding::new(
                &rules::SDF_UNDEFINED_FRAME,
                reference.span,
                format!("'{}' names no frame of the model", reference.written),
            )
            .with_help(help),
        );
        reference.fallback.clone()
    }

    /// The pose of frame `name` in the analysed model's frame; `None` when it lies on a cycle.
    pub fn pose(&mut self, name: &str) -> Option<Transform> {
        let mut chain: Vec<String> = Vec::new();
        let mut on_chain: HashSet<String> = HashSet::new();
        let mut current = name.to_string();
        let base = loop {
            if current.is_empty() {
                break Some(Transform::identity());
            }
            if current == "world" {
                break Some(self.scene.model_pose.inverse());
            }
            if let Some(known) = self.poses.get(&current) {
                break *known;
            }
            let Some(def) = self.scene.frames.get(&current) else {
                break None;
            };
            if !on_chain.insert(current.clone()) {
                self.report(
                    &rules::SDF_FRAME_CYCLE,
                    def.span,
                    format!("the pose of '{current}' is relative to a chain of frames that comes back to it: {} → {current}", chain.join(" → ")),
                );
                break None;
            }
            chain.push(current.clone());
            let reference = def.relative_to.clone();
            current = self.target(&reference);
        };
        let mut pose = base;
        for frame in chain.iter().rev() {
            pose = pose.and_then(|p| Some(p * self.scene.frames.get(frame)?.pose));
            self.poses.insert(frame.clone(), pose);
        }
        if chain.is_empty() {
            base
        } else {
            self.poses.get(name).copied().flatten()
        }
    }

    /// The link frame `name` is attached to (`world` for the world); `None` on a cycle, or for a model
    /// without links. Memoised for every frame on the way, so a chain of n frames costs O(n) in all.
    pub fn link_of(&mut self, name: &str) -> Option<String> {
        let mut visited: Vec<String> = Vec::new();
        let mut on_chain: HashSet<String> = HashSet::new();
        let mut current = name.to_string();
        let link = loop {
            if current == "world" {
                break Some(current);
            }
            if let Some(known) = self.links.get(&current) {
                break known.clone();
            }
            let next = if current.is_empty() {
                self.scene.canonical.clone()
            } else {
                let Some(def) = self.scene.frames.get(&current) else {
                    break None;
                };
                match &def.kind {
                    Kind::Link => break Some(current),
                    Kind::Joint { child } => Some(child.clone()),
                    Kind::Frame { attached_to } => Some(attached_to.clone()),
                    Kind::Model { canonical } => canonical.clone(),
                }
            };
            if !on_chain.insert(current.clone()) {
                let span = self
                    .scene
                    .frames
                    .get(&current)
                    .map_or(self.scene.span, |d| d.span);
                self.report(
                    &rules::SDF_FRAME_CYCLE,
                    span,
                    format!("'{current}' is attached to a chain of frames that comes back to it, so it is attached to no link"),
                );
                break None;
            }
            visited.push(current.clone());
            let Some(next) = next else {
                break None;
            };
            current = self.target(&next);
        };
        for frame in visited {
            self.links.insert(frame, link.clone());
        }
        link
    }
}
