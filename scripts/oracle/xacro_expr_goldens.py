#!/usr/bin/env python3
"""Differential goldens for the native `${...}` evaluator (crates/xacro/src/expr).

Evaluates every expression below exactly as Python xacro 2.1.1 does (`xacro.safe_eval` with the symbols of
`xacro.create_global_symbols()` under a property `Table`) and writes
crates/xacro/tests/golden/expr/cases.tsv, which `crates/xacro/src/expr/golden_tests.rs` replays without
Python.

Usage (outside the repo's environments):
    python3 -m venv /tmp/xv && /tmp/xv/bin/pip install xacro==2.1.1 pyyaml
    /tmp/xv/bin/python scripts/oracle/xacro_expr_goldens.py

File format, one record per line, fields separated by TAB, with backslash escapes (\\\\, \\t, \\n, \\r):
    prop  NAME  EXPR          property NAME = value of EXPR (evaluated with the built-ins only)
    case  EXPR  ok   STR      str() of the result
    case  EXPR  err  CLASS    the exception class name

Left out on purpose (the native evaluator models them differently, see the module docs): reprs of
iterator and class objects (`range(3)`, `zip(...)`, `map(...)`, `list`), `lambda`, and `dict.items()` views
(materialised as lists natively).

Expressions found in real xacro files (../shared/robots and example-robot-data when installed in .venv)
are appended; every name they use that is neither a built-in nor a property below gets a float property.
"""

import glob
import io
import os
import re
import sys
import contextlib

import xacro

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
OUT = os.path.join(REPO, "crates", "xacro", "tests", "golden", "expr", "cases.tsv")

# Properties visible to every case: (name, expression evaluated with the built-ins only).
PROPS = [
    ("wheel_radius", "0.1"),
    ("n", "3"),
    ("neg", "-7"),
    ("f", "2.5"),
    ("name", "'arm'"),
    ("s", "'Hello World'"),
    ("csv", "'a, b;c,,d'"),
    ("reflect", "-1"),
    ("flag", "True"),
    ("off", "False"),
    ("nothing", "None"),
    ("empty", "''"),
    ("l", "[1, 2, 3]"),
    ("fl", "[0.5, -1.25, 3.0]"),
    ("words", "['b', 'a', 'c']"),
    ("t", "(4, 5, 6)"),
    ("nested", "[[1, 2], [3, 4]]"),
    ("d", "dict(a=1, b='two', c=[1, 2])"),
    ("cfg", "xacro.dotify(dict(mass=2.5, inner=dict(x=1, y=[1, 2]), joints=['j1', 'j2'], on=True))"),
    ("M_PI", "3.1415926535897931"),
    ("radians", "0.5"),  # a property shadowing a built-in
    ("mass_str", "'1.5'"),
]

CASES = r"""
# literals
0
42
-5
1_000_000
0x1F
0o17
0b101
0xff_ff
1.
.5
1e-3
1E3
1.5e+10
1_0.5
1e-5
1e16
1e15
0.0001
0.00001
123456789012345.6
-0.0
0.1
1/3
2/3
100.0
1e100
5e-324
'abc'
"abc"
'it\'s'
"say \"hi\""
'tab\there'
'a\\b'
'\x41\u00e9'
r'raw\n'
'con' 'cat'
''
True
False
None
[1, 2.0, 'a']
[]
(1,)
()
(1, 2)
1, 2
[[1, 'x'], ('y', None)]
{'a': 1}
{'a': 1, 'b': [1, 2]}
{1: 'x', 2.5: None}
{}
["it's"]
['a"b']
["a'b\"c"]
['\n']
# arithmetic
1 + 2
1 + 2 * 3
(1 + 2) * 3
7 / 2
6 / 2
-7 / 2
7 // 2
-7 // 2
7 // -2
-7 // -2
7 % 3
-7 % 3
7 % -3
-7 % -3
7.5 // 2
-7.5 // 2
7.5 % 2
-7.5 % 2
7.5 % -2
5 % 0.7
2 ** 10
2 ** -1
2 ** 0.5
-2 ** 2
(-2) ** 2
2 ** 3 ** 2
2.0 ** 3
(-8) ** 3
0 ** 0
10 ** 18
-1 ** 0.5
4 ** 0.5
True + True
True * 3
False - 1
1 + 2.5
0.1 + 0.2
0.1 * 3
1e308 * 10
-1e308 * 10
3 - 5
-(-3)
+5
-f
+f
~5
~-1
5 & 3
5 | 3
5 ^ 3
True & False
True | False
1 << 10
1024 >> 3
-16 >> 2
-13/3 * 127.532/15.28
-1 * 624/35 * 80/18
(729.0/25.0)*(22.0/16.0)
0.0833333 * 1.1 * (0.102*0.102 + 0.152*0.152)
reflect * M_PI/4 + 1.5
55.0/180.0*M_PI
-M_PI/2
1 / 0
1 // 0
1 % 0
1.0 / 0
1.0 // 0.0
1.0 % 0.0
0 ** -1
0.0 ** -1
1 + 'a'
'a' + 1
[1] + (2,)
'a' - 'b'
-'a'
~1.5
1.5 & 1
1 << -1
[1] * 'a'
# strings and sequences arithmetic
'ab' + 'cd'
'ab' * 3
3 * 'ab'
'ab' * 0
'ab' * -2
[1, 2] * 2
(1,) * 3
[1] + [2, 3]
(1, 2) + (3,)
'x' * True
# comparisons
1 < 2
2 < 1
1 < 2 < 3
1 < 3 < 2
3 > 2 > 1
1 <= 1 < 2
1 == 1.0
1 == True
0 == False
2 == True
1 != 1.0
'a' == 'a'
'a' < 'b'
'B' < 'a'
'abc' < 'abd'
'ab' < 'abc'
[1, 2] < [1, 3]
[1, 2] < [1, 2, 0]
(1, 2) == (1, 2)
[1, 2] == (1, 2)
[1, 2] == [1.0, 2.0]
None == None
None == 0
'1' == 1
1 < 'a'
None < 1
[1] < (1,)
float('nan') == float('nan')
float('nan') < 1
1 < float('inf')
9007199254740993 == 9007199254740992.0
9007199254740993 > 9007199254740992.0
{'a': 1} == {'a': 1.0}
# membership and identity
2 in l
5 in l
5 not in l
'a' in 'abc'
'ac' in 'abc'
'' in 'abc'
'a' in d
'z' in d
'mass' in cfg
1 in 'abc'
1 in 5
1 in t
[1, 2] in nested
None is None
nothing is None
nothing is not None
n is None
n is not None
True is True
# boolean logic
True and False
True or False
not True
not 0
not ''
not []
not None
1 and 2
0 and 2
1 or 2
0 or 2
'' or 'default'
empty or name
name and empty
flag and n
off or nothing
None or 0
not n == 3
not 1 < 2
flag or undefined_thing
off and undefined_thing
1 if True else 2
1 if False else 2
'yes' if flag else 'no'
'yes' if empty else 'no'
1 if off else 2 if flag else 3
(n if n > 2 else 0) + 1
# names
wheel_radius
wheel_radius * 2
name
undefined_name
undefined_name + 1
wheel_radus * 2
radians
radians(180)
math.radians(180)
pi
math.pi
e
math.e
tau
inf
math.inf
-inf
nan
math.nan
M_PI
# builtins exposed bare
len(l)
len('héllo')
len(d)
len(t)
len(5)
str(1)
str(1.0)
str(1e-5)
str(True)
str(None)
str(l)
str()
float(3)
float('1e3')
float(' 2.5 ')
float('inf')
float('-Infinity')
float('nan')
float('1_000.5')
float(True)
float('abc')
float('')
float([1])
float()
int(3.9)
int(-3.9)
int('3')
int(' -42 ')
int('1_000')
int('0x1f', 16)
int('0x1f', 0)
int('ff', 16)
int('101', 2)
int(True)
int('3.5')
int('')
int(float('inf'))
int(float('nan'))
int([1])
int()
bool(0)
bool(1)
bool('')
bool('False')
bool([])
bool()
list('abc')
list((1, 2))
list(d)
list()
list(5)
dict(a=1, b=2)
dict([('a', 1), ('b', 2)])
dict(d, e=5)
dict()
dict([1, 2])
dict([(1, 2, 3)])
min(3, 1, 2)
min(l)
min(words)
min([])
min([], default=0)
min(l, key=float)
min('hello')
min(1, 'a')
max(3, 1, 2)
max(fl)
max(1, 2.5)
max([3, 3.0])
max([True, 1])
round(2.5)
round(3.5)
round(-2.5)
round(0.5)
round(1.5)
round(2.675, 2)
round(0.125, 2)
round(0.375, 2)
round(1.23456, 3)
round(1234.5678, -2)
round(1250.0, -2)
round(1350, -2)
round(1250, -2)
round(-1251, -2)
round(7, 2)
round(2.5, 0)
round(-0.4)
round(1e20)
round(float('inf'))
round(float('nan'))
round('a')
round(2.5, None)
sorted([3, 1, 2])
sorted(words)
sorted(words, reverse=True)
sorted(fl, key=abs)
sorted([1, 'a'])
sorted('bca')
sorted(d)
list(range(5))
list(range(2, 5))
list(range(0, 10, 3))
list(range(5, 0, -2))
list(range(0))
list(range(5, 2))
range(0, 10, 0)
range(1.5)
list(range(3))
list(map(float, l))
list(map(str, l))
list(map(int, ['1', '2']))
list(map(max, l, [2, 2, 2]))
map(float, 5)
# python namespace
python.abs(-3)
python.abs(-2.5)
python.abs(True)
python.abs('a')
python.all([1, 2])
python.all([1, 0])
python.all([])
python.any([0, ''])
python.any([0, 1])
python.sum(l)
python.sum(fl)
python.sum([0.1] * 10)
python.sum([[1], [2]], [])
python.sum(l, 10)
python.sum(['a'], '')
python.tuple(l)
python.tuple('ab')
python.list(python.zip(l, 'ab'))
python.divmod(7, 2)
python.divmod(-7, 2)
python.divmod(7.5, 2)
python.divmod(1, 0)
python.ord('a')
python.ord('ab')
python.repr('a')
python.repr(1.0)
python.repr(l)
python.list(python.reversed('abc'))
python.len(l)
python.str(2)
python.True
python.False
python.min(l)
python.round(1.5)
python.sorted(words)
python.bool(1)
python.float('2')
python.list(python.filter(bool, [0, 1]))
python.nope
python.int('7')
python.dict(a=1)
abs(-3)
sum(l)
zip(l, l)
tuple(l)
# math
sin(0)
cos(0)
tan(0)
sin(M_PI / 2)
math.sin(1)
math.cos(1)
math.tan(1)
asin(1)
acos(0)
atan(1)
atan2(1, 1)
atan2(-1, -1)
math.atan2(0, -1)
sinh(1)
cosh(1)
tanh(1)
asinh(1)
acosh(1)
atanh(0.5)
sqrt(2)
sqrt(16)
sqrt(-1)
math.sqrt(4)
exp(1)
exp(0)
exp(1000)
expm1(1e-10)
log(math.e)
log(100, 10)
log(8, 2)
log(0)
log(-1)
log(1, 1)
log10(1000)
log2(8)
log1p(1e-10)
pow(2, 10)
pow(2, 0.5)
pow(0, -1)
pow(-8, 1.0 / 3)
math.pow(10, 400)
fabs(-2)
floor(2.5)
floor(-2.5)
ceil(2.1)
ceil(-2.1)
floor(5)
trunc(-2.7)
math.floor(1e300)
floor(float('inf'))
degrees(M_PI)
degrees(1)
radians(90)
math.radians(90)
hypot(3, 4)
hypot(1, 2, 2)
hypot()
copysign(1, -0.0)
copysign(3, -1)
fmod(7, 3)
fmod(-7, 3)
fmod(1, 0)
remainder(7, 2)
remainder(5, 2)
remainder(-7, 2)
isclose(1.0, 1.0 + 1e-10)
isclose(1.0, 1.1)
isclose(1.0, 1.1, rel_tol=0.2)
isclose(0, 1e-10, abs_tol=1e-9)
isfinite(1.0)
isinf(inf)
isnan(nan)
math.isnan(1)
factorial(5)
factorial(0)
factorial(-1)
factorial(20)
gcd(12, 18)
gcd(0, 5)
gcd()
lcm(4, 6)
comb(5, 2)
perm(5, 2)
perm(5)
isqrt(17)
isqrt(-1)
frexp(8.0)
frexp(-0.1)
frexp(0.0)
ldexp(0.5, 4)
modf(3.5)
modf(-3.5)
fsum([0.1] * 10)
fsum([1e100, 1.0, -1e100])
prod(l)
prod(fl)
prod([])
dist([0, 0], [3, 4])
nextafter(1.0, 2.0)
ulp(1.0)
cbrt(27)
exp2(10)
math.tau
sin('a')
sqrt()
sqrt(1, 2)
math.nope
math.sin.x
# indexing and slicing
l[0]
l[-1]
l[2]
l[3]
l[-4]
l[True]
l['a']
l[1.0]
t[1]
t[-1]
nested[1][0]
name[0]
name[-1]
name[5]
'héllo'[1]
d['a']
d['c'][1]
d['z']
d[[1]]
cfg['mass']
cfg['inner']['x']
5[0]
None[0]
l[1:]
l[:2]
l[:]
l[::-1]
l[::2]
l[-2:]
l[5:]
l[-100:100]
l[2:1]
l[::0]
l[1:None]
l['a':]
t[1:]
name[1:]
name[::-1]
s[6:]
s[-5:-1]
'héllo'[1:3]
l[0:3:2]
l[3:0:-1]
l[-1:-4:-1]
# attributes, YAML dicts
cfg.mass
cfg.inner.x
cfg.inner.y[1]
cfg.joints[0]
cfg.on
cfg.nope
cfg.inner.nope
len(cfg)
len(cfg.joints)
'inner' in cfg
d.get('a')
d.get('z')
d.get('z', 5)
list(d.keys())
list(d.values())
list(d.items())
len(d.items())
sorted(d.keys())
l.count(2)
l.index(2)
l.index(9)
t.index(5)
t.count(9)
(1.5).is_integer()
(2.0).is_integer()
(255).bit_length()
(1).real
l.nope
5 .nope
name.nope
# string methods
name.upper()
s.lower()
s.upper()
s.title()
'hello world'.capitalize()
s.swapcase()
'  pad  '.strip()
'  pad  '.lstrip()
'  pad  '.rstrip()
'xxpadxx'.strip('x')
'a b  c'.split()
'  a b  '.split()
'a,b,,c'.split(',')
'a,b,c'.split(',', 1)
'a,b,c'.rsplit(',', 1)
'a b c'.rsplit(None, 1)
'a b c'.split(maxsplit=1)
''.split()
''.split(',')
'a,b'.split('')
'l1\nl2\r\nl3'.splitlines()
s.replace('o', '0')
s.replace('o', '0', 1)
'aaa'.replace('a', 'b', 2)
'ab'.replace('', '-')
'{}_{}'.format(name, 1)
'{0}{1}{0}'.format('a', 'b')
'{x}-{y}'.format(x=1, y=2)
'{:.3f}'.format(M_PI)
'{:>8}|'.format('r')
'{:<8}|'.format('l')
'{:^8}|'.format('c')
'{:*^9}'.format('c')
'{:08.3f}'.format(-M_PI)
'{:+d}'.format(5)
'{: d}'.format(5)
'{:,}'.format(1234567)
'{:_}'.format(1234567)
'{:,.2f}'.format(1234567.891)
'{:x}'.format(255)
'{:#x}'.format(255)
'{:#o}'.format(8)
'{:b}'.format(5)
'{:08b}'.format(5)
'{:e}'.format(12345.678)
'{:.2e}'.format(0.000123)
'{:g}'.format(0.00001234)
'{:g}'.format(1234567)
'{:.3g}'.format(1234.5)
'{:.3}'.format(1.0)
'{:.3}'.format(1234.5)
'{:.1%}'.format(0.256)
'{:%}'.format(0.5)
'{}'.format(1.0)
'{}'.format(1e-7)
'{}'.format([1, 'a'])
'{!r}'.format('a')
'{!s}'.format(1.5)
'{:5}|'.format(1.5)
'{:5}|'.format('ab')
'{:d}'.format(True)
'{}'.format(True)
'{:.2f}'.format(1)
'{0[1]}'.format(l)
'{0[a]}'.format(d)
'{:{w}}|'.format(1, w=4)
'{{literal}}'.format()
'{}'.format()
'{} {}'.format(1)
'{0} {}'.format(1, 2)
'{z}'.format(a=1)
'{:d}'.format('a')
'{:d}'.format(1.5)
'{:s}'.format(1)
'}'.format()
'{'.format()
'{:=5}'.format('a')
s.startswith('Hello')
s.startswith(('x', 'He'))
s.endswith('World')
s.endswith('x')
s.startswith('World', 6)
'-'.join(words)
''.join(['a', 'b'])
', '.join(map(str, l))
'-'.join([1, 2])
'-'.join('abc')
s.find('o')
s.rfind('o')
s.find('z')
s.index('W')
s.index('z')
s.count('o')
s.count('')
'héllo'.find('l')
'123'.isdigit()
'12a'.isdigit()
'abc'.isalpha()
'ab1'.isalnum()
'  '.isspace()
'ABC'.isupper()
'abc'.islower()
'a_b'.isidentifier()
'42'.zfill(5)
'-42'.zfill(5)
'ab'.center(7)
'ab'.center(6, '*')
'abc'.center(6)
'ab'.ljust(5, '.')
'ab'.rjust(5)
'a=b=c'.partition('=')
'a=b=c'.rpartition('=')
'abc'.partition('x')
'prefix_name'.removeprefix('prefix_')
'name.urdf'.removesuffix('.urdf')
s.upper().lower()
name.upper() + '_link'
s.split()[1].lower()
s.nope()
s.upper(1)
name.center('a')
# percent formatting
'%05d' % 7
'%d' % 7
'%d' % -7
'%d' % 7.9
'%d' % True
'%i' % 3
'%5d|' % 42
'%-5d|' % 42
'%+d' % 5
'% d' % 5
'%.3d' % 5
'%x' % 255
'%X' % 255
'%#x' % 255
'%o' % 8
'%#o' % 8
'%s_%s' % ('a', 'b')
'%s' % 'x'
'%s' % 1.0
'%s' % [1, 2]
'%s' % (l,)
'%r' % 'x'
'%r' % 1.5
'%10s|' % 'r'
'%-10s|' % 'l'
'%.2s' % 'abc'
'%f' % M_PI
'%.3f' % M_PI
'%.0f' % 2.5
'%.0f' % 3.5
'%#.0f' % 2.0
'%8.3f|' % -1.5
'%08.3f' % -1.5
'%+.2f' % 1
'%e' % 12345.678
'%.2e' % 0.000123
'%E' % 1e-10
'%g' % 0.00001234
'%g' % 1234567
'%g' % 123456
'%g' % 100000.0
'%g' % 1e-4
'%g' % 0.0
'%g' % 1.5
'%.3g' % M_PI
'%#g' % 1.5
'%G' % 1e-10
'%f' % float('inf')
'%f' % float('nan')
'%5.1f%%' % 99.5
'%c' % 65
'%c' % 'z'
'%(a)s and %(b)s' % d
'%(a)05d' % d
'%*d' % (5, 3)
'%.*f' % (2, M_PI)
'%s %s' % 'a'
'%s' % (1, 2)
'%d' % 'a'
'%x' % 1.5
'%f' % 'a'
'%z' % 1
'%' % 1
'100%' % ()
'%s' % ()
'%s' % None
'%s-%d' % (name, n)
'%.4f' % (1.0 / 3.0)
# comprehensions
[x * 2 for x in l]
[x for x in l if x > 1]
[x + y for x in l for y in t]
[(i, w) for i, w in python.enumerate(words)]
[k for k in d]
[c.upper() for c in 'ab']
{k: v for k, v in python.zip(words, l)}
[x for x in 5]
[a for a, b in [(1, 2, 3)]]
python.sum(x * x for x in l)
python.any(x > 2 for x in l)
min(x for x in fl)
[y for y in [x for x in l]]
x
[x for x in l] and x
# syntax errors and refused names
1 +
(1
[1, 2
1 2
a b
import os
x := 1
f'{n}'
b'abc'
1j
1__0
007
'abc
"abc'
1 if 2
{1, 2}
l[1:2, 3]
__import__('os')
().__class__.__bases__
''.__class__
l.__len__()
__builtins__
__name__
eval('1')
exec('1')
open('/etc/passwd')
compile('1', '', 'eval')
getattr(l, 'x')
globals()
locals()
vars()
type(1)
isinstance(1, int)
set([1])
hash(1)
complex(1)
print(1)
input()
"""


def esc(text):
    return text.replace("\\", "\\\\").replace("\t", "\\t").replace("\n", "\\n").replace("\r", "\\r")


def real_file_expressions():
    roots = [os.path.join(REPO, "..", "shared", "robots")]
    roots += glob.glob(os.path.join(REPO, ".venv", "lib", "python3*", "site-packages", "cmeel.prefix", "share",
                                    "example-robot-data", "robots"))
    found = set()
    for root in roots:
        for dirpath, _, files in os.walk(root):
            for fn in files:
                if not fn.endswith((".xacro", ".urdf", ".urdf.xacro", ".gazebo")):
                    continue
                try:
                    with open(os.path.join(dirpath, fn), encoding="utf-8", errors="replace") as fh:
                        text = fh.read()
                except OSError:
                    continue
                for m in re.finditer(r"\$\{([^}]*)\}", text):
                    expr = m.group(1)
                    if "$(" in expr or "\n" in expr or "\t" in expr or not expr.strip():
                        continue
                    found.add(expr)
    return sorted(found)


def main():
    glob_syms = xacro.create_global_symbols()
    symbols = xacro.Table(glob_syms)
    lines = []

    def define(name, expr):
        value = xacro.safe_eval(expr, xacro.Table(glob_syms))
        dict.__setitem__(symbols, name, value)
        lines.append("prop\t%s\t%s" % (name, esc(expr)))

    for name, expr in PROPS:
        define(name, expr)

    cases = [c for c in CASES.strip("\n").split("\n") if c and not c.startswith("# ")]
    real = real_file_expressions()
    # Names used by real files that are neither built-ins nor properties get a float value.
    missing = set()
    for expr in real:
        try:
            code = compile(expr.strip(), "<expression>", "eval")
        except SyntaxError:
            continue
        for n in code.co_names:
            if n not in glob_syms and not dict.__contains__(symbols, n) and not n.startswith("_"):
                missing.add(n)
    for i, n in enumerate(sorted(missing)):
        define(n, repr((i % 13 + 1) / 8.0))

    seen = set()
    for expr in cases + real:
        if expr in seen:
            continue
        seen.add(expr)
        with contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
            try:
                result = xacro.safe_eval(expr, symbols)
                outcome = ("ok", str(result))
            except Exception as e:  # noqa: BLE001 - the class name is the golden
                outcome = ("err", type(e).__name__)
        lines.append("case\t%s\t%s\t%s" % (esc(expr), outcome[0], esc(outcome[1])))

    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w", encoding="utf-8") as fh:
        fh.write("\n".join(lines) + "\n")
    print("wrote %d cases (%d from real files) to %s" % (len(seen), len(real), os.path.relpath(OUT, REPO)),
          file=sys.stderr)


if __name__ == "__main__":
    main()
