//! Text evaluation: `eval_text` (`${...}`, `$(...)`, `$$` escapes), the scopes expressions see,
//! properties with lazy evaluation, and the host functions (`load_yaml`, `xacro.*`, `$(eval)` helpers).

use super::*;

/// Names in an expression that start with `__` (outside string literals): Python xacro refuses them.
pub(super) fn dunder_names(code: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut chars = code.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c == '\'' || c == '"' {
            let mut escaped = false;
            for (_, d) in chars.by_ref() {
                if escaped {
                    escaped = false;
                } else if d == '\\' {
                    escaped = true;
                } else if d == c {
                    break;
                }
            }
        } else if c == '_' || c.is_alphabetic() {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = chars.peek() {
                if d == '_' || d.is_alphanumeric() {
                    end = j + d.len_utf8();
                    chars.next();
                } else {
                    break;
                }
            }
            let word = &code[i..end];
            if word.starts_with("__") {
                names.push(word.to_string());
            }
        } else if c.is_ascii_digit() {
            while chars
                .peek()
                .is_some_and(|&(_, d)| d.is_alphanumeric() || d == '_' || d == '.')
            {
                chars.next();
            }
        }
    }
    names
}

/// The scope `${...}` expressions see: properties, then host functions.
pub(super) struct PropScope<'a, 'o> {
    x: &'a Expander<'o>,
    symbols: &'a TableRef,
    ctx: &'a Ctx,
}

impl Scope for PropScope<'_, '_> {
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError> {
        self.x
            .lookup_property(self.symbols, name, self.ctx)
            .map_err(|e| self.x.stash(e))
    }

    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        self.x.call_host(name, args, kwargs, self.ctx)
    }
}

/// The scope of `$(eval ...)`: arguments (converted as roslaunch does), `true`/`false`, and the functions
/// `arg`, `dirname`, `env`, `optenv`, `find`.
pub(super) struct ArgScope<'a, 'o> {
    x: &'a Expander<'o>,
    ctx: &'a Ctx,
}

impl Scope for ArgScope<'_, '_> {
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError> {
        Ok(match name {
            "true" | "True" => Some(Value::Bool(true)),
            "false" | "False" => Some(Value::Bool(false)),
            "arg" | "dirname" | "env" | "optenv" | "find" => {
                Some(Value::Function(format!("xacro.eval_{name}").into()))
            }
            _ => self
                .x
                .args
                .borrow()
                .get(name)
                .map(|v| substitution::convert_auto(v)),
        })
    }

    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        self.x.call_host(name, args, kwargs, self.ctx)
    }
}

/// A scope with no properties (built-ins only).
pub(super) struct NoScope;

impl Scope for NoScope {
    fn lookup(&self, _: &str) -> Result<Option<Value>, EvalError> {
        Ok(None)
    }

    fn call_host(
        &self,
        _: &str,
        _: &[Value],
        _: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        None
    }
}

pub(super) fn host_error(kind: &'static str, message: String) -> EvalError {
    EvalError {
        kind,
        message,
        undefined_name: None,
        offset: None,
    }
}

fn too_long() -> XacroError {
    XacroError::new(ErrorKind::Limit, "a string exceeds the output size limit")
}

pub(super) fn str_arg(args: &[Value], i: usize) -> Option<String> {
    args.get(i).map(Value::to_xacro_string)
}

impl Expander<'_> {
    // ----------------------------------------------------------------------------------------------------
    // Text evaluation: eval_text, ${...}, $(...)

    /// Python xacro's `eval_text`: one token returns its typed value, several are joined as text.
    pub(super) fn eval_text(
        &self,
        text: &str,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<Value, XacroError> {
        if !text.contains('$') {
            return Ok(Value::Str(text.into()));
        }
        let mut results: Vec<Value> = Vec::new();
        let mut rest = text;
        while !rest.is_empty() {
            let dollars = rest.bytes().take_while(|&b| b == b'$').count();
            if dollars >= 2 && matches!(rest.as_bytes().get(dollars), Some(b'{' | b'(')) {
                results.push(Value::Str(rest[1..=dollars].into()));
                rest = &rest[dollars + 1..];
            } else if let Some(inner) = rest
                .strip_prefix("${")
                .and_then(|r| r.find('}').map(|i| &r[..i]))
            {
                results.push(self.handle_expr(inner, symbols, ctx)?);
                rest = &rest[inner.len() + 3..];
            } else if let Some(inner) = rest
                .strip_prefix("$(")
                .and_then(|r| r.find(')').map(|i| &r[..i]))
            {
                results.push(self.handle_extension(inner, symbols, ctx)?);
                rest = &rest[inner.len() + 3..];
            } else if dollars == 0 {
                let end = rest.find('$').unwrap_or(rest.len());
                results.push(Value::Str(rest[..end].into()));
                rest = &rest[end..];
            } else if dollars == 1 && rest.len() == 1 {
                results.push(Value::Str("$".into()));
                rest = "";
            } else if dollars == 1 && !matches!(rest.as_bytes().get(1), Some(b'{' | b'(')) {
                let end = rest[1..]
                    .find(['{', '(', '$'])
                    .map_or(rest.len(), |i| i + 1);
                results.push(Value::Str(rest[..end].into()));
                rest = &rest[end..];
            } else {
                return Err(XacroError::new(
                    ErrorKind::Expression,
                    format!("invalid expression: {rest}"),
                ));
            }
        }
        if results.len() == 1 {
            return Ok(results.pop().unwrap_or(Value::None));
        }
        // Checked as it grows: the parts may each be near the limit (and share one string).
        let mut joined = String::new();
        for r in &results {
            match r {
                Value::Str(s) => joined.push_str(s),
                v => joined.push_str(&self.text_within_limit(v)?),
            }
            if joined.len() > self.opts.limits.max_output_bytes {
                return Err(too_long());
            }
        }
        Ok(Value::Str(joined.into()))
    }

    pub(super) fn parse_expr(&self, code: &str) -> Result<Rc<expr::Expr>, EvalError> {
        if let Some(e) = self.exprs.borrow().get(code) {
            return Ok(e.clone());
        }
        let parsed = Rc::new(expr::parse(code)?);
        self.exprs
            .borrow_mut()
            .insert(code.to_string(), parsed.clone());
        Ok(parsed)
    }

    /// `${inner}`.
    pub(super) fn handle_expr(
        &self,
        inner: &str,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<Value, XacroError> {
        let code = self.eval_text(inner, symbols, ctx)?.to_xacro_string();
        let bad = dunder_names(&code);
        if !bad.is_empty() {
            return Err(XacroError::new(
                ErrorKind::InvalidName,
                format!(
                    "Use of invalid name(s): {} in expression '${{{inner}}}'",
                    bad.join(", ")
                ),
            ));
        }
        let scope = PropScope {
            x: self,
            symbols,
            ctx,
        };
        let result = self
            .parse_expr(code.trim())
            .and_then(|e| expr::eval(&e, &scope));
        let value = match result {
            Ok(v) => {
                self.pending.borrow_mut().take();
                v
            }
            Err(e) => {
                if let Some(detail) = self.pending.borrow_mut().take() {
                    return Err(detail);
                }
                return Err(self.expr_error(e, inner, Some(symbols)));
            }
        };
        match &value {
            Value::Str(s) if s.len() > self.opts.limits.max_output_bytes => return Err(too_long()),
            // Containers share their items, so a short expression can build a list whose text is
            // exponentially long: make sure it fits before it is used as text anywhere.
            Value::List(_)
            | Value::Tuple(_)
            | Value::Dict(_)
            | Value::Set(_)
            | Value::FrozenSet(_) => {
                self.text_within_limit(&value)?;
            }
            _ => {}
        }
        Ok(value)
    }

    /// `str(v)`, or a limit error when longer than the output size limit.
    fn text_within_limit(&self, v: &Value) -> Result<String, XacroError> {
        v.to_xacro_string_within(self.opts.limits.max_output_bytes)
            .map_err(|_| too_long())
    }

    pub(super) fn expr_error(
        &self,
        e: EvalError,
        inner: &str,
        symbols: Option<&TableRef>,
    ) -> XacroError {
        if e.kind == "NameError" {
            let hint = match (&e.undefined_name, symbols) {
                (Some(name), Some(t)) => {
                    let names = t.visible_names();
                    did_you_mean(name, names.iter().map(String::as_str))
                }
                _ => String::new(),
            };
            return XacroError::new(
                ErrorKind::UndefinedProperty,
                format!("{}{hint}, when evaluating expression '{inner}'", e.message),
            );
        }
        XacroError::new(
            ErrorKind::Expression,
            format!(
                "{}: {}, when evaluating expression '{inner}'",
                e.kind, e.message
            ),
        )
    }

    /// `$(inner)`.
    pub(super) fn handle_extension(
        &self,
        inner: &str,
        symbols: &TableRef,
        ctx: &Ctx,
    ) -> Result<Value, XacroError> {
        let inner = self.eval_text(inner, symbols, ctx)?.to_xacro_string();
        let s = format!("$({inner})");
        if s == "$(cwd)" {
            let cwd = std::env::current_dir().unwrap_or_default();
            return Ok(Value::Str(cwd.display().to_string().into()));
        }
        if let Some(code) = s.strip_prefix("$(eval ").and_then(|r| r.strip_suffix(')')) {
            if code.contains("__") {
                return Err(XacroError::new(
                    ErrorKind::InvalidName,
                    "$(eval ...) may not contain double underscore expressions",
                ));
            }
            let scope = ArgScope { x: self, ctx };
            let result = self
                .parse_expr(code.trim())
                .and_then(|e| expr::eval(&e, &scope));
            return match result {
                Ok(v) => {
                    self.pending.borrow_mut().take();
                    Ok(Value::Str(self.text_within_limit(&v)?.into()))
                }
                Err(e) => match self.pending.borrow_mut().take() {
                    Some(detail) => Err(detail),
                    None => Err(self.expr_error(e, &s, None)),
                },
            };
        }
        let host = SubstHost { x: self };
        substitution::resolve_args(&s, &host).map(|v| Value::Str(v.into()))
    }

    pub(super) fn arg_value(&self, name: &str) -> Result<String, XacroError> {
        self.known_args.borrow_mut().insert(name.to_string());
        let args = self.args.borrow();
        args.get(name).cloned().ok_or_else(|| {
            let hint = did_you_mean(name, args.keys().map(String::as_str));
            XacroError::new(
                ErrorKind::UndefinedArgument,
                format!("Undefined substitution argument {name}{hint}"),
            )
        })
    }

    /// A variable the expander looks up for itself (`$(find)`'s `AMENT_PREFIX_PATH`, `ROS_PACKAGE_PATH`): a
    /// refused one is unset, silently.
    pub(super) fn env_var(&self, name: &str) -> Option<String> {
        if let Some(gate) = &self.opts.gate {
            if gate.env(name).is_err() {
                return None;
            }
        }
        match &self.opts.env {
            Some(env) => env(name),
            None => std::env::var(name).ok(),
        }
    }

    /// A variable the input asks for (`$(env)`, `$(optenv)`): a refused one is reported as a refusal.
    pub(super) fn asked_env(&self, name: &str) -> Result<Option<String>, Refused> {
        if let Some(Err(why)) = self.opts.gate.as_ref().map(|gate| gate.env(name)) {
            self.refuse(format!(
                "refused to read environment variable '{name}': {why}"
            ));
            return Err(Refused);
        }
        Ok(self.env_var(name))
    }

    pub(super) fn find_package(&self, pkg: &str) -> Result<String, XacroError> {
        let current = self.current_file();
        // Every file of a package asks the same question: cache by (package, folder of the current file).
        let key = (
            pkg.to_string(),
            current.parent().map(Path::to_path_buf).unwrap_or_default(),
        );
        let cached = self.packages.borrow().get(&key).cloned();
        let found = match cached {
            Some(found) => found,
            None => {
                let env = |n: &str| self.env_var(n);
                let found = include::find_package(pkg, self.opts, &env, &current)
                    .map(|p| p.display().to_string());
                self.packages.borrow_mut().insert(key, found.clone());
                found
            }
        };
        found.map_err(|searched| {
            let where_ = if searched.is_empty() {
                String::new()
            } else {
                format!("; searched: {}", searched.join(", "))
            };
            let hint = self
                .opts
                .package_hint
                .as_deref()
                .map(|h| format!("; {h}"))
                .unwrap_or_default();
            XacroError::new(
                ErrorKind::PackageNotFound,
                format!("package '{pkg}' not found{where_}{hint}"),
            )
        })
    }

    pub(super) fn dirname(&self) -> Result<String, XacroError> {
        let current = self.current_file();
        let abs = std::path::absolute(&current).unwrap_or(current);
        Ok(abs
            .parent()
            .map(|p| p.display().to_string())
            .unwrap_or_default())
    }

    // ----------------------------------------------------------------------------------------------------
    // Properties and host functions

    /// `symbols[name]` with lazy evaluation; `Ok(None)` when no property has that name.
    pub(super) fn lookup_property(
        &self,
        symbols: &TableRef,
        name: &str,
        ctx: &Ctx,
    ) -> Result<Option<Value>, XacroError> {
        let Some(table) = symbols.find(name) else {
            return Ok(None);
        };
        let entry = table.entries.borrow().get(name).cloned();
        match entry {
            None | Some(Entry::Block(_)) => Ok(None),
            Some(Entry::Value(v)) => Ok(Some(v)),
            Some(Entry::Namespace(ns)) => {
                let keys: Vec<String> = ns
                    .entries
                    .borrow()
                    .keys()
                    .filter(|k| is_valid_name(k))
                    .cloned()
                    .collect();
                let mut items = Vec::new();
                for k in keys {
                    if let Ok(Some(v)) = self.lookup_property(&ns, &k, ctx) {
                        items.push((Value::Str(k.into()), v));
                    }
                }
                Ok(Some(Value::Dict(Rc::new(items))))
            }
            Some(Entry::Lazy(text, def)) => {
                if table.resolving.borrow().iter().any(|n| n == name) {
                    let mut chain = table.resolving.borrow().clone();
                    chain.push(name.to_string());
                    let e = XacroError::new(
                        ErrorKind::CircularProperty,
                        format!(
                            "circular variable definition: {}. Consider disabling lazy evaluation via lazy_eval=\"false\"",
                            chain.join(" -> ")
                        ),
                    );
                    return Err(match def {
                        Some(l) => self.locate(e, l, ctx),
                        None => e,
                    });
                }
                // Chains of lazy properties recurse: bound them like element nesting.
                self.check_stack()?;
                let depth = self.nesting.get() + 1;
                if depth > self.opts.limits.max_nesting {
                    return Err(XacroError::new(
                        ErrorKind::Limit,
                        format!(
                            "properties refer to each other more than {} levels deep",
                            self.opts.limits.max_nesting
                        ),
                    ));
                }
                self.nesting.set(depth);
                table.resolving.borrow_mut().push(name.to_string());
                let result = self.eval_text(&text, &table, ctx);
                table.resolving.borrow_mut().retain(|n| n != name);
                self.nesting.set(depth - 1);
                let value = match result {
                    Ok(v) => v,
                    Err(e) => {
                        return Err(match def {
                            Some(l) => self.locate(e, l, ctx),
                            None => e,
                        })
                    }
                };
                let value = match value {
                    Value::Str(s) => crate::properties::eval_literal(&s),
                    v => v,
                };
                table
                    .entries
                    .borrow_mut()
                    .insert(name.to_string(), Entry::Value(value.clone()));
                Ok(Some(value))
            }
        }
    }

    /// `name in symbols`, built-ins included.
    pub(super) fn has_symbol(&self, symbols: &TableRef, name: &str) -> bool {
        symbols.find(name).is_some() || self.is_builtin(name)
    }

    pub(super) fn is_builtin(&self, name: &str) -> bool {
        if let Some(&known) = self.builtins.borrow().get(name) {
            return known;
        }
        let builtin = is_valid_name(name)
            && expr::parse(name)
                .and_then(|e| expr::eval(&e, &NoScope))
                .is_ok();
        self.builtins.borrow_mut().insert(name.to_string(), builtin);
        builtin
    }

    /// Python xacro's warning when a property or parameter shadows a built-in name.
    pub(super) fn warn_if_builtin(&self, name: &str, loc: Loc, ctx: &Ctx) {
        if self.is_builtin(name) {
            self.warn(format!("redefining global symbol: {name}"), Some(loc), ctx);
        }
    }

    pub(super) fn call_host(
        &self,
        name: &str,
        args: &[Value],
        kwargs: &[(String, Value)],
        ctx: &Ctx,
    ) -> Option<Result<Value, EvalError>> {
        let name = name.strip_prefix("python.").unwrap_or(name);
        let result = match name {
            "xacro.load_yaml" | "load_yaml" => {
                let spec = str_arg(args, 0).unwrap_or_default();
                self.load_yaml(&spec).map_err(|e| self.stash(e))
            }
            "xacro.abs_filename" | "abs_filename" => {
                let spec = str_arg(args, 0).unwrap_or_default();
                Ok(Value::Str(
                    include::abs_filename(&spec, &self.current_file())
                        .display()
                        .to_string()
                        .into(),
                ))
            }
            "xacro.arg" | "xacro.eval_arg" => {
                let n = str_arg(args, 0).unwrap_or_default();
                match self.arg_value(&n) {
                    Ok(v) if name == "xacro.eval_arg" => Ok(substitution::convert_auto(&v)),
                    Ok(v) => Ok(Value::Str(v.into())),
                    Err(e) => Err(self.stash(e)),
                }
            }
            "xacro.message" | "xacro.warning" | "xacro.error" | "xacro.print_location" => {
                let text: Vec<String> = args.iter().map(Value::to_xacro_string).collect();
                // At the innermost macro call (or include), with the calls that led there.
                let loc = ctx.frame.as_ref().map(|f| f.loc);
                let outer = Ctx {
                    frame: ctx.frame.as_ref().and_then(|f| f.parent.clone()),
                    ..ctx.clone()
                };
                if name != "xacro.print_location" {
                    self.warn(text.join(" "), loc, &outer);
                }
                Ok(Value::Str("".into()))
            }
            "xacro.fatal" => {
                let text: Vec<String> = args.iter().map(Value::to_xacro_string).collect();
                Err(self.stash(XacroError::new(ErrorKind::Fatal, text.join(" "))))
            }
            "xacro.dotify" | "dotify" => Ok(args.first().cloned().unwrap_or(Value::None)),
            "xacro.tokenize" => {
                let s = str_arg(args, 0).unwrap_or_default();
                let kw = |k: &str| kwargs.iter().find(|(n, _)| n == k).map(|(_, v)| v.clone());
                let sep = args
                    .get(1)
                    .cloned()
                    .or_else(|| kw("sep"))
                    .map_or(",; ".to_string(), |v| v.to_xacro_string());
                let skip_empty = args
                    .get(2)
                    .cloned()
                    .or_else(|| kw("skip_empty"))
                    .is_none_or(|v| v.is_truthy());
                let items = s
                    .split(|c| sep.contains(c))
                    .filter(|t| !skip_empty || !t.is_empty())
                    .map(|t| Value::Str(t.into()))
                    .collect();
                Ok(Value::List(Rc::new(items)))
            }
            "xacro.eval_dirname" => self
                .dirname()
                .map(|d| Value::Str(d.into()))
                .map_err(|e| self.stash(e)),
            "xacro.eval_env" => {
                let n = str_arg(args, 0).unwrap_or_default();
                match self.asked_env(&n) {
                    Ok(Some(v)) => Ok(Value::Str(v.into())),
                    Ok(None) => Err(host_error("KeyError", format!("'{n}'"))),
                    Err(Refused) => Ok(Value::Str("".into())),
                }
            }
            "xacro.eval_optenv" => {
                let n = str_arg(args, 0).unwrap_or_default();
                let default = str_arg(args, 1).unwrap_or_default();
                let value = self.asked_env(&n).ok().flatten();
                Ok(Value::Str(value.unwrap_or(default).into()))
            }
            "xacro.eval_find" => {
                let n = str_arg(args, 0).unwrap_or_default();
                self.find_package(&n)
                    .map(|p| Value::Str(p.into()))
                    .map_err(|e| self.stash(e))
            }
            _ => return None,
        };
        Some(result)
    }

    pub(super) fn load_yaml(&self, spec: &str) -> Result<Value, XacroError> {
        let path = include::abs_filename(spec, &self.current_file());
        if let Some(value) = self.yaml_files.borrow().get(&path) {
            return Ok(value.clone());
        }
        if let Some(Err(why)) = self.opts.gate.as_ref().map(|gate| gate.file(&path)) {
            // Not read: an empty mapping stands in for it (a later lookup in it fails, with this refusal noted).
            self.refuse(format!("refused to read YAML file '{spec}': {why}"));
            return Ok(Value::Dict(Rc::default()));
        }
        let text = include::read_text(&path, self.opts.limits.max_output_bytes).map_err(|e| {
            XacroError::new(
                ErrorKind::Io,
                format!("cannot read YAML file {}: {e}", path.display()),
            )
        })?;
        self.sources
            .borrow_mut()
            .push(SourceFile::new(path.clone(), text.clone()));
        let eval = |s: &str| expr::parse(s.trim()).and_then(|e| expr::eval(&e, &NoScope));
        let value = crate::yaml::load(&text, &eval).map_err(|e| {
            XacroError::new(
                ErrorKind::Yaml,
                format!("{}: {} (in {})", e.kind, e.message, path.display()),
            )
        })?;
        self.yaml_files.borrow_mut().insert(path, value.clone());
        Ok(value)
    }
}

/// `$(...)` host: arguments, environment, packages, the current directory.
pub(super) struct SubstHost<'a, 'o> {
    x: &'a Expander<'o>,
}

impl SubstitutionHost for SubstHost<'_, '_> {
    fn arg(&self, name: &str) -> Result<String, XacroError> {
        self.x.arg_value(name)
    }

    fn env(&self, name: &str) -> Result<Option<String>, Refused> {
        self.x.asked_env(name)
    }

    fn find(&self, pkg: &str) -> Result<String, XacroError> {
        self.x.find_package(pkg)
    }

    fn dirname(&self) -> Result<String, XacroError> {
        self.x.dirname()
    }
}
