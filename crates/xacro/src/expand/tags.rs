//! The xacro tags with state: `xacro:property`, `xacro:macro` definitions and calls, `xacro:include`,
//! and the blocks of `xacro:insert_block`.

use super::*;

impl Expander<'_> {
    pub(super) fn block(&self, symbols: &TableRef, key: &str) -> Option<NodeRef> {
        let table = symbols.find(key)?;
        let entry = table.entries.borrow().get(key).cloned();
        match entry {
            Some(Entry::Block(b)) => Some(b),
            _ => None,
        }
    }

    /// `grab_property`.
    pub(super) fn property(
        &self,
        node: &NodeRef,
        el: &Element,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let attrs = self.check_attrs(
            node,
            el,
            &["name"],
            &["value", "default", "remove", "scope", "lazy_eval"],
            ctx,
        )?;
        let [Some(name_attr), value, default, remove, scope, lazy_eval] = attrs[..] else {
            return Ok(());
        };
        let name = self.eval_attr(name_attr, symbols, ctx)?.to_xacro_string();
        if !is_valid_name(&name) {
            let e = XacroError::new(
                ErrorKind::InvalidName,
                format!("Property names must be valid python identifiers: {name}"),
            );
            return Err(self.locate(e, name_attr.src.loc, ctx));
        }
        if name.starts_with("__") {
            let e = XacroError::new(
                ErrorKind::InvalidName,
                format!("Property names must not start with double underscore:{name}"),
            );
            return Err(self.locate(e, name_attr.src.loc, ctx));
        }
        let bool_attr = |a: Option<&Attr>, default: bool| -> Result<bool, XacroError> {
            let Some(a) = a else { return Ok(default) };
            let v = self.eval_attr(a, symbols, ctx)?;
            boolean_value(&v).ok_or_else(|| {
                let e = XacroError::new(
                    ErrorKind::BadCondition,
                    format!(
                        "Xacro conditional \"{}\" evaluated to \"{}\", which is not a boolean expression.",
                        a.value,
                        v.to_xacro_string()
                    ),
                );
                self.locate(e, a.src.loc, ctx)
            })
        };
        let remove = bool_attr(remove, false)?;
        if usize::from(value.is_some()) + usize::from(default.is_some()) + usize::from(remove) > 1 {
            let e = XacroError::new(
                ErrorKind::Other,
                format!(
                    "Property attributes default, value, and remove are mutually exclusive: {name}"
                ),
            );
            return Err(self.locate(e, loc, ctx));
        }
        if remove && self.has_symbol(symbols, &name) {
            symbols.remove(&name);
            return Ok(());
        }
        let mut value = value;
        if let Some(d) = default {
            if scope.is_some() {
                self.warn(
                    format!("{name}: default property value can only be defined on local scope"),
                    Some(loc),
                    ctx,
                );
            }
            if self.has_symbol(symbols, &name) {
                return Ok(());
            }
            value = Some(d);
        }
        let mut lazy = bool_attr(lazy_eval, true)?;
        let target = match scope.map(|a| &*a.value) {
            Some("global") => {
                lazy = false;
                symbols.top()
            }
            Some("parent") => match symbols.parent() {
                Some(parent) => {
                    lazy = false;
                    let mut target = parent;
                    if !symbols.is_namespace {
                        while target.is_namespace {
                            match target.parent() {
                                Some(p) => target = p,
                                None => break,
                            }
                        }
                    }
                    target
                }
                None => {
                    let e = XacroError::new(
                        ErrorKind::Other,
                        format!("{name}: scope=\"parent\" used at global scope, which has no parent scope"),
                    );
                    return Err(self.locate(e, loc, ctx));
                }
            },
            _ => symbols.clone(),
        };
        if value.is_some() {
            self.warn_if_builtin(&name, loc, ctx);
        }
        match value {
            None => target.set_entry(&format!("**{name}"), Entry::Block(node.clone())),
            Some(v) if !lazy => {
                let evaluated = self.eval_attr(v, symbols, ctx)?;
                target.set_value(&name, evaluated);
            }
            Some(v) => target.set_text(&name, &v.value, true, Some(v.src.loc)),
        }
        Ok(())
    }

    /// `grab_macro`.
    pub(super) fn define_macro(
        &self,
        node: &NodeRef,
        el: &Element,
        macros: &MacroTableRef,
        ctx: &Ctx,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let attrs = self.check_attrs(node, el, &["name"], &["params"], ctx)?;
        let [Some(name_attr), params] = attrs[..] else {
            return Ok(());
        };
        let mut name: &str = &name_attr.value;
        if name == "call" {
            return Err(self.locate(
                XacroError::new(ErrorKind::Other, "Invalid use of macro name 'call'"),
                loc,
                ctx,
            ));
        }
        if name.contains('.') {
            let e = XacroError::new(
                ErrorKind::Other,
                format!("macro names must not contain '.' (reserved for namespaces): {name}"),
            );
            return Err(self.locate(e, loc, ctx));
        }
        if let Some(stripped) = name.strip_prefix("xacro:") {
            self.warn(
                format!("macro names must not contain prefix 'xacro:': {name}"),
                Some(loc),
                ctx,
            );
            name = stripped;
        }
        let mut m = Macro {
            params: Vec::new(),
            defaults: HashMap::new(),
            body: node.clone(),
        };
        for (param, spec) in parse_params(params.map_or("", |p| &*p.value)) {
            if let Some(spec) = spec {
                m.defaults.insert(param.clone(), spec);
            }
            m.params.push(param);
        }
        macros
            .entries
            .borrow_mut()
            .insert(name.to_string(), MacroEntry::Macro(Rc::new(m)));
        Ok(())
    }

    /// `resolve_macro`: the macro, and the macro and symbol tables it is called with.
    pub(super) fn resolve_macro(
        &self,
        fullname: &str,
        macros: &MacroTableRef,
        symbols: &TableRef,
    ) -> Option<(MacroTableRef, TableRef, Rc<Macro>)> {
        if let Some(MacroEntry::Macro(m)) = macros.get(fullname) {
            return Some((macros.clone(), symbols.clone(), m));
        }
        let mut parts: Vec<&str> = fullname.split('.').collect();
        let name = parts.pop()?;
        if parts.is_empty() {
            return None;
        }
        let (mut m, mut s) = (macros.clone(), symbols.clone());
        for ns in parts {
            let MacroEntry::Namespace(next_m) = m.get(ns)? else {
                return None;
            };
            let table = s.find(ns)?;
            let entry = table.entries.borrow().get(ns).cloned();
            let Some(Entry::Namespace(next_s)) = entry else {
                return None;
            };
            m = next_m;
            s = next_s;
        }
        match m.get(name)? {
            MacroEntry::Macro(found) => Some((m, s, found)),
            MacroEntry::Namespace(_) => None,
        }
    }

    /// `handle_macro_call` (and `handle_dynamic_macro_call`).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn macro_call(
        &self,
        node: &NodeRef,
        el: &Element,
        out: &mut Vec<NodeRef>,
        parent_attrs: &mut Vec<Attr>,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
        has_next: bool,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let (name, call_attrs): (String, Vec<&Attr>) = if &*el.name == "xacro:call" {
            let Some(macro_attr) = el.attrs.iter().find(|a| &*a.name == "macro") else {
                let e = XacroError::new(
                    ErrorKind::MissingAttribute,
                    "xacro:call: missing attribute 'macro'",
                );
                return Err(self.locate(e, loc, ctx));
            };
            if macro_attr.value.is_empty() {
                let e = XacroError::new(
                    ErrorKind::MissingAttribute,
                    "xacro:call is missing the 'macro' attribute",
                );
                return Err(self.locate(e, loc, ctx));
            }
            let name = self.eval_attr(macro_attr, symbols, ctx)?.to_xacro_string();
            if name == "call" {
                let e = XacroError::new(
                    ErrorKind::MissingAttribute,
                    "xacro:call: missing attribute 'macro'",
                );
                return Err(self.locate(e, loc, ctx));
            }
            (
                name,
                el.attrs.iter().filter(|a| &*a.name != "macro").collect(),
            )
        } else {
            (
                el.name["xacro:".len()..].to_string(),
                el.attrs.iter().collect(),
            )
        };
        let Some((ns_macros, ns_symbols, m)) = self.resolve_macro(&name, macros, symbols) else {
            let names = macros.visible_names();
            let hint = did_you_mean(&name, names.iter().map(String::as_str));
            let e = XacroError::new(
                ErrorKind::UnknownMacro,
                format!("unknown macro name: xacro:{name}{hint}"),
            );
            return Err(self.locate(e, loc, ctx));
        };
        if ctx.macro_depth >= self.opts.limits.max_macro_depth {
            let e = XacroError::new(
                ErrorKind::Limit,
                format!(
                    "macro calls nested deeper than {} levels (runaway recursion?) when calling '{name}'",
                    self.opts.limits.max_macro_depth
                ),
            );
            return Err(self.locate(e, loc, ctx));
        }
        let frame = Rc::new(FrameData {
            kind: FrameKind::Macro,
            name: name.clone(),
            loc,
            parent: ctx.frame.clone(),
        });
        let call_ctx = Ctx {
            frame: Some(frame),
            macro_depth: ctx.macro_depth + 1,
            include_depth: ctx.include_depth,
        };
        let scoped_symbols = Table::child(&ns_symbols, false);
        let scoped_macros = MacroTable::child(&ns_macros);
        let mut params = m.params.clone();
        for a in call_attrs {
            let Some(pos) = params.iter().position(|p| **p == *a.name) else {
                let hint = did_you_mean(&a.name, m.params.iter().map(String::as_str));
                let e = XacroError::new(
                    ErrorKind::UnknownParameter,
                    format!("Invalid parameter \"{}\" of macro '{name}'{hint}", a.name),
                );
                return Err(self.locate(e, a.name_loc, ctx));
            };
            params.remove(pos);
            let value = self.eval_attr(a, symbols, ctx)?;
            self.warn_if_builtin(&a.name, a.name_loc, ctx);
            scoped_symbols.set_value(&a.name, value);
        }
        // The call's children (blocks) are evaluated in the caller's scope.
        let mut call_children = Vec::new();
        let mut call_attrs_out = Vec::new();
        self.process_children(
            &el.children,
            &mut call_children,
            &mut call_attrs_out,
            macros,
            symbols,
            ctx,
        )?;
        let mut blocks = call_children
            .iter()
            .filter(|n| matches!(n.kind, Kind::Element(_)));
        for param in params.clone() {
            if param.starts_with('*') {
                let Some(block) = blocks.next() else {
                    let e = XacroError::new(
                        ErrorKind::Block,
                        format!("Not enough blocks for macro '{name}'"),
                    );
                    return Err(self.locate(e, loc, ctx));
                };
                params.retain(|p| *p != param);
                scoped_symbols.set_entry(&param, Entry::Block(block.clone()));
            }
        }
        if let Some(extra) = blocks.next() {
            let tag = match &extra.kind {
                Kind::Element(e) => e.name.to_string(),
                _ => String::new(),
            };
            let e = XacroError::new(
                ErrorKind::Block,
                format!("Unused block \"{tag}\" in call of macro '{name}'"),
            );
            return Err(self.locate(e, extra.src.loc, ctx));
        }
        for param in params.clone() {
            if param.starts_with('*') {
                continue;
            }
            if let Some((forward, default)) = m.defaults.get(&param) {
                self.at.set(Some(loc));
                let value = match forward {
                    None => self.eval_text(default.as_deref().unwrap_or(""), symbols, ctx),
                    Some(fwd) => match self.lookup_property(symbols, fwd, ctx)? {
                        Some(v) => Ok(v),
                        None => match default {
                            Some(d) => self.eval_text(d, symbols, ctx),
                            None => Err(XacroError::new(
                                ErrorKind::UndefinedProperty,
                                format!("Undefined property to forward: {fwd}"),
                            )),
                        },
                    },
                }
                .map_err(|e| self.locate(e, loc, ctx))?;
                self.warn_if_builtin(&param, loc, ctx);
                scoped_symbols.set_value(&param, value);
                params.retain(|p| *p != param);
            }
        }
        if !params.is_empty() {
            let e = XacroError::new(
                ErrorKind::MissingParameter,
                format!(
                    "Undefined parameters [{}] in call of macro '{name}'",
                    params.join(",")
                ),
            );
            return Err(self.locate(e, loc, ctx));
        }
        let body = self.eval_element(&m.body, &scoped_macros, &scoped_symbols, &call_ctx)?;
        let sep = self.remove_previous_comments(out, has_next);
        self.import_namespaces(parent_attrs, &body.attrs, loc, ctx);
        out.extend(body.children);
        if sep {
            self.push_separator(out, &node.src);
        }
        Ok(())
    }

    /// `process_include`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn include(
        &self,
        node: &NodeRef,
        el: &Element,
        out: &mut Vec<NodeRef>,
        parent_attrs: &mut Vec<Attr>,
        macros: &MacroTableRef,
        symbols: &TableRef,
        ctx: &Ctx,
        has_next: bool,
    ) -> Result<(), XacroError> {
        let loc = node.src.loc;
        let attrs = self.check_attrs(node, el, &["filename"], &["ns", "optional"], ctx)?;
        let [Some(filename), ns, optional] = attrs[..] else {
            return Ok(());
        };
        let (ns_macros, ns_symbols) = match ns {
            Some(ns) => {
                let ns_name = self.eval_attr(ns, symbols, ctx)?.to_xacro_string();
                let ns_macros: MacroTableRef = Rc::default();
                macros
                    .entries
                    .borrow_mut()
                    .insert(ns_name.clone(), MacroEntry::Namespace(ns_macros.clone()));
                let ns_symbols = Table::child(symbols, true);
                symbols.set_entry(&ns_name, Entry::Namespace(ns_symbols.clone()));
                (ns_macros, ns_symbols)
            }
            None => (macros.clone(), symbols.clone()),
        };
        let optional = match optional {
            None => false,
            Some(a) => boolean_value(&Value::Str(a.value.clone())).ok_or_else(|| {
                let e = XacroError::new(
                    ErrorKind::BadCondition,
                    format!("Xacro conditional \"None\" evaluated to \"{}\", which is not a boolean expression.", a.value),
                );
                self.locate(e, a.src.loc, ctx)
            })?,
        };
        if el
            .children
            .iter()
            .any(|c| matches!(c.kind, Kind::Element(_)))
        {
            self.warn(
                "Child elements of a <xacro:include> tag are ignored".into(),
                Some(loc),
                ctx,
            );
        }
        let spec = self.eval_attr(filename, symbols, ctx)?.to_xacro_string();
        let path = include::abs_filename(&spec, &self.current_file());
        let path_text = path.display().to_string();
        let refused = |why: String| format!("refused to read include '{spec}': {why}");
        let files = if include::is_glob(&path_text) {
            let listed = include::glob_folder(&path);
            if let Some(Err(why)) = self.opts.gate.as_ref().map(|gate| gate.dir(&listed)) {
                self.warn_refused(refused(why), loc, ctx);
                return Ok(());
            }
            let files = include::glob_files(&path_text);
            if files.is_empty() {
                self.warn(
                    format!("Include tag's filename spec \"{path_text}\" matched no files."),
                    Some(loc),
                    ctx,
                );
            }
            files
        } else {
            vec![path]
        };
        let mut included = Vec::new();
        for file in files {
            if let Some(Err(why)) = self.opts.gate.as_ref().map(|gate| gate.file(&file)) {
                self.warn_refused(refused(why), loc, ctx);
                continue;
            }
            if ctx.include_depth >= self.opts.limits.max_include_depth {
                let e = XacroError::new(
                    ErrorKind::Limit,
                    format!(
                        "includes nested deeper than {} levels",
                        self.opts.limits.max_include_depth
                    ),
                );
                return Err(self.locate(e, loc, ctx));
            }
            let canonical = Some(lexical_absolute(&file));
            let cycle = canonical.is_some() && self.open_files.borrow().contains(&canonical);
            if cycle {
                let e = XacroError::new(
                    ErrorKind::IncludeCycle,
                    format!(
                        "include cycle: {} includes itself (directly or through other files)",
                        file.display()
                    ),
                );
                return Err(self.locate(e, loc, ctx));
            }
            let frame = Rc::new(FrameData {
                kind: FrameKind::Include,
                name: file.display().to_string(),
                loc,
                parent: ctx.frame.clone(),
            });
            let inc_ctx = Ctx {
                frame: Some(frame),
                macro_depth: ctx.macro_depth,
                include_depth: ctx.include_depth + 1,
            };
            let doc = match self.load(&file) {
                Ok(doc) => doc,
                Err(e)
                    if optional && matches!(e.kind, ErrorKind::IncludeNotFound | ErrorKind::Io) =>
                {
                    continue
                }
                // Invalid XML in the included file: located there, through this include.
                Err(mut e) if e.location.is_some() => {
                    e.stack = self.stack(&inc_ctx);
                    return Err(e);
                }
                Err(e) => return Err(self.locate(e, filename.src.loc, ctx)),
            };
            let Some(root) = doc.root().cloned() else {
                continue;
            };
            self.file_stack.borrow_mut().push(file);
            self.open_files.borrow_mut().push(canonical);
            let built = self.eval_element(&root, &ns_macros, &ns_symbols, &inc_ctx);
            self.file_stack.borrow_mut().pop();
            self.open_files.borrow_mut().pop();
            let built = built?;
            self.import_namespaces(parent_attrs, &built.attrs, loc, ctx);
            included.extend(built.children);
        }
        let sep = self.remove_previous_comments(out, has_next);
        out.extend(included);
        if sep {
            self.push_separator(out, &node.src);
        }
        Ok(())
    }
}
