//! The frame graph of a [`Scene`]: every frame's pose in the model frame (following `relative_to`), and
//! the link each frame is attached to (following `attached_to`, a joint's child, a model's canonical
//! link). Cycles and names that do not exist are findings, never a loop or a panic.

use std::collections::{HashMap, HashSet};

use super::pose::Transform;
use super::scene::{Kind, Ref, Scene};
use crate::diagnostics::finding::Finding;
use crate::diagnostics::rules;
use crate::diagnostics::suggest::did_you_mean;
use crate::input::source::Span;

/// Resolves poses and attachments of one scene, memoising them.
pub struct FrameGraph<'s, 'a> {
    scene: &'s Scene<'a>,
    poses: HashMap<String, Option<Transform>>,
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
        let help = did_you_mean(
            &reference.name,
            self.scene.frames.keys().map(String::as_str),
        );
        self.report(
            &rules::SDF_UNDEFINED_FRAME,
            reference.span,
            format!("'{}' names no frame of the model{help}", reference.written),
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
    /// without links.
    pub fn link_of(&mut self, name: &str) -> Option<String> {
        let mut seen: HashSet<String> = HashSet::new();
        let mut current = name.to_string();
        loop {
            if current == "world" {
                return Some(current);
            }
            let next = if current.is_empty() {
                self.scene.canonical.clone()
            } else {
                let def = self.scene.frames.get(&current)?;
                match &def.kind {
                    Kind::Link => return Some(current),
                    Kind::Joint { child } => Some(child.clone()),
                    Kind::Frame { attached_to } => Some(attached_to.clone()),
                    Kind::Model { canonical } => canonical.clone(),
                }
            };
            if !seen.insert(current.clone()) {
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
                return None;
            }
            current = self.target(&next?);
        }
    }
}
