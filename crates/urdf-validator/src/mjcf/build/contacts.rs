//! Which body pairs MuJoCo never lets collide, as link pairs for the self-collision check: a
//! `<contact><exclude body1 body2>`, a pair none of whose geoms pass MuJoCo's filter (two geoms collide
//! only when `contype1 & conaffinity2` or `contype2 & conaffinity1` is not 0), and MuJoCo's parent filter
//! bodies welded together (to the same moving body, or to the world) never collide, and (unless
//! `<option><flag filterparent="disable">`) nor does a body with the body its own weld hangs from, the
//! world excepted (MuJoCo's `body_weldid` rule).

use std::collections::{HashMap, HashSet};

use super::Builder;
use crate::mjcf::xml::El;
use crate::urdf::robot::contact_bits_meet;

/// What the contact filter needs to know of a body.
pub(super) struct BodyContacts {
    /// Its link.
    pub link: String,
    /// Its parent body's link (`world` for a top-level body).
    pub parent: String,
    /// It has a joint (is not welded to its parent).
    pub moving: bool,
    /// `(contype, conaffinity)` of each of its collision geoms.
    pub geoms: Vec<(u32, u32)>,
}

/// The bodies by their link's name.
pub(super) fn by_link(bodies: &[BodyContacts]) -> HashMap<&str, &BodyContacts> {
    bodies.iter().map(|b| (b.link.as_str(), b)).collect()
}

/// The weld root of the body whose link is `link`: itself when it moves, else its parent's (the world's
/// link name for none): MuJoCo's `body_weldid`. Names are keys, and a file may repeat one (a body inside an
/// ancestor of its own name, which MuJoCo refuses and U101 reports): the walk stops after as many steps as
/// there are bodies, so a name that leads back to itself cannot hold it forever.
pub(super) fn weld_root(by_link: &HashMap<&str, &BodyContacts>, link: &str) -> String {
    let mut at = link;
    for _ in 0..=by_link.len() {
        match by_link.get(at).filter(|b| !b.moving) {
            Some(body) => at = &body.parent,
            None => break,
        }
    }
    at.to_string()
}

impl<'a> Builder<'a, '_> {
    /// The link pairs MuJoCo never lets collide, given the `<contact>` and `<option>` sections among
    /// `sections`; each pair once, sorted.
    pub(super) fn filtered_pairs(&mut self, sections: &[El<'a>]) -> Vec<(String, String)> {
        let mut pairs: HashSet<(String, String)> = HashSet::new();
        let mut add = |a: &str, b: &str| {
            if a != b {
                let (a, b) = if a < b { (a, b) } else { (b, a) };
                pairs.insert((a.to_string(), b.to_string()));
            }
        };
        let mut filter_parent = true;
        // Only these two sections: expanding another's includes again would repeat their U031s.
        for section in sections
            .iter()
            .filter(|s| matches!(s.tag(), "contact" | "option"))
        {
            for el in self.reader.children(*section) {
                match (section.tag(), el.tag()) {
                    ("contact", "exclude") => {
                        if let (Some(a), Some(b)) = (el.attr("body1"), el.attr("body2")) {
                            add(a, b);
                        }
                    }
                    ("option", "flag") if el.attr("filterparent") == Some("disable") => {
                        filter_parent = false;
                    }
                    _ => {}
                }
            }
        }
        let bodies = &self.body_contacts;
        let by_link = by_link(bodies);
        let weld_root = |link: &str| weld_root(&by_link, link);
        let roots: Vec<String> = bodies.iter().map(|b| weld_root(&b.link)).collect();
        let parent_roots: Vec<Option<String>> = roots
            .iter()
            .map(|r| by_link.get(r.as_str()).map(|b| weld_root(&b.parent)))
            .collect();
        for (i, a) in bodies.iter().enumerate() {
            for (j, b) in bodies.iter().enumerate().skip(i + 1) {
                if a.geoms.is_empty() || b.geoms.is_empty() {
                    continue;
                }
                let never = !a
                    .geoms
                    .iter()
                    .any(|&g| b.geoms.iter().any(|&h| contact_bits_meet(g, h)));
                let world = roots[i] == "world" || roots[j] == "world";
                let family = roots[i] == roots[j]
                    || (filter_parent
                        && !world
                        && (parent_roots[i].as_deref() == Some(roots[j].as_str())
                            || parent_roots[j].as_deref() == Some(roots[i].as_str())));
                if never || family {
                    add(&a.link, &b.link);
                }
            }
        }
        let mut pairs: Vec<(String, String)> = pairs.into_iter().collect();
        pairs.sort();
        pairs
    }
}
