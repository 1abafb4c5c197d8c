"""Reads interfaces/*.lcm: the one definition of every message, for the build-time generators
(gen_csv_writers.py, gen_telemetry.py) and the plotting tools.

lcm-gen ignores comments; we keep them, and read the tags in them that bind a message to the
C++ structs it is filled from (interfaces/README.md):
  before `struct`:  @fill             generate reentry::fill(msg&, const Sources&...)
                    @core TYPE        also generate TYPE, a plain struct of the fields (no LCM)
  after a field:    @from PATH        the source member when its name is not the field's
                    @value LITERAL    no source: always this value
                    @default LITERAL  initial value of the member of the @core struct
                    @enum TYPE HEADER the @core member's enum type and its header
                    @bits             one bool per constant FIELD_NAME = bit mask
Tags close a comment line: `// text @tag args`.
"""
import re
from dataclasses import dataclass, field as dc_field

PRIMITIVES = {"int8_t", "int16_t", "int32_t", "int64_t", "byte", "float",
              "double", "boolean", "string"}
INTEGERS = {"int8_t", "int16_t", "int32_t", "int64_t", "byte"}
TAG_ARITY = {"fill": 0, "core": 1, "from": 1, "value": 1, "default": 1, "enum": 2, "bits": 0}
STRUCT_TAGS = {"fill", "core"}
STAMPS = ("utime", "tick")  # every message's time stamp: set by the caller, never copied


class SchemaError(Exception):
    pass


@dataclass
class Const:
    type: str
    name: str
    value: str
    comment: str = ""


@dataclass
class Field:
    type: str
    name: str
    length: int = 0            # 0: scalar; n: fixed array of n
    comment: str = ""
    tags: dict = dc_field(default_factory=dict)
    line: int = 0


@dataclass
class Struct:
    package: str
    name: str
    path: str
    comment: str = ""
    tags: dict = dc_field(default_factory=dict)
    consts: list = dc_field(default_factory=list)
    fields: list = dc_field(default_factory=list)

    @property
    def cpp_name(self):
        return "::".join(self.package.split(".") + [self.name]) if self.package else self.name

    def field(self, name):
        return next((f for f in self.fields if f.name == name), None)

    def consts_of(self, field_name):
        """The constants that name the values (or bits) of a field: FIELD_NAME_..."""
        prefix = field_name.upper() + "_"
        return [c for c in self.consts if c.name.startswith(prefix)]


def split_tags(text, where):
    """Human text and {tag: [args]} of one comment line."""
    tokens = text.split()
    words, tags, i = [], {}, 0
    while i < len(tokens):
        t = tokens[i]
        if t.startswith("@") and len(t) > 1:
            name = t[1:]
            if name not in TAG_ARITY:
                raise SchemaError(f"{where}: unknown tag @{name} (known: {', '.join(sorted(TAG_ARITY))})")
            n = TAG_ARITY[name]
            args = tokens[i + 1:i + 1 + n]
            if len(args) != n or any(a.startswith("@") for a in args):
                raise SchemaError(f"{where}: @{name} takes {n} argument(s)")
            tags[name] = [a.strip('"') for a in args]
            i += 1 + n
        else:
            words.append(t)
            i += 1
    return " ".join(words), tags


def _dims(path, line, fname, dims_txt, consts):
    dims = []
    for d in re.findall(r"\[\s*(\w+)\s*\]", dims_txt):
        if d.isdigit():
            dims.append(int(d))
        elif d in consts and consts[d].value.lstrip("-").isdigit():
            dims.append(int(consts[d].value))
        else:
            raise SchemaError(f"{path}:{line}: field '{fname}' has variable length [{d}]; "
                              "only fixed-size arrays are supported")
    if len(dims) > 1:
        raise SchemaError(f"{path}:{line}: field '{fname}' is multi-dimensional (unsupported)")
    return dims[0] if dims else 0


def _statement(st, stmt, line, comment, tags):
    """Adds one member statement (a constant list or a field) to the struct."""
    where = f"{st.path}:{line}"
    if stmt.startswith("const "):
        m = re.match(r"const\s+(\w+)\s+(.*)$", stmt)
        if not m:
            raise SchemaError(f"{where}: cannot parse constant '{stmt}'")
        for part in m.group(2).split(","):
            cm = re.match(r"\s*(\w+)\s*=\s*(\S+)\s*$", part)
            if not cm:
                raise SchemaError(f"{where}: cannot parse constant '{part.strip()}'")
            st.consts.append(Const(m.group(1), cm.group(1), cm.group(2), comment))
        if tags:
            raise SchemaError(f"{where}: tags belong on fields, not on constants")
        return
    fm = re.match(r"([\w.]+)\s+(\w+)\s*((?:\[\s*\w+\s*\])*)$", stmt)
    if not fm:
        raise SchemaError(f"{where}: cannot parse field '{stmt}'")
    ftype, fname, dims_txt = fm.groups()
    length = _dims(st.path, line, fname, dims_txt, {c.name: c for c in st.consts})
    if STRUCT_TAGS & set(tags):
        raise SchemaError(f"{where}: @{sorted(STRUCT_TAGS & set(tags))[0]} belongs before `struct`")
    st.fields.append(Field(ftype, fname, length, comment, tags, line))


class _Reader:
    """Line-oriented reader: a comment on a statement's line (or on the lines after it, indented
    deeper) belongs to that statement; comment lines before `struct` belong to the struct."""

    def __init__(self, path):
        self.path = path
        self.package = ""
        self.structs = []
        self.pending = []        # comment lines not yet attached
        self.current = None      # struct being read
        self.code = ""           # statement text up to its ';'
        self.last = None         # (item, indent) of the last statement, for continuation lines

    def comment_line(self, text, indent, line):
        last = self.last
        if last is not None and indent > last[1]:
            human, tags = split_tags(text, f"{self.path}:{line}")
            item = last[0]
            item.comment = (item.comment + " " + human).strip()
            item.tags.update(tags)
        else:
            self.pending.append((text, line))
            self.last = None

    def take_pending(self):
        human, tags = [], {}
        for text, line in self.pending:
            h, t = split_tags(text, f"{self.path}:{line}")
            human.append(h)
            tags.update(t)
        self.pending = []
        return " ".join(x for x in human if x), tags

    def code_line(self, code, comment, indent, line):
        self.code = (self.code + " " + code).strip()
        while True:
            self.code = self.code.strip()
            if self.current is None:
                if not self._outside(line):
                    return
                continue
            if self.code.startswith("}"):
                self.current, self.code, self.last = None, self.code[1:], None
                continue
            if ";" not in self.code:
                return
            stmt, self.code = self.code.split(";", 1)
            stmt = " ".join(stmt.split())
            human, tags = self.take_pending()
            if stmt.startswith("const "):
                human = ""  # a comment line before constants heads the group; each keeps its own
            if comment is not None and not self.code.strip():
                h, t = split_tags(comment, f"{self.path}:{line}")
                human = (human + " " + h).strip()
                tags.update(t)
            _statement(self.current, stmt, line, human, tags)
            item = self.current.fields[-1] if not stmt.startswith("const ") else self.current.consts[-1]
            self.last = (item if isinstance(item, Field) else None, indent)
            if self.last[0] is None:
                self.last = None

    def _outside(self, line):
        """Package and struct headers. False when more text is needed."""
        m = re.match(r"package\s+([\w.]+)\s*;", self.code)
        if m:
            self.package, self.code = m.group(1), self.code[m.end():]
            self.pending = []
            return True
        m = re.match(r"struct\s+(\w+)\s*\{", self.code)
        if m:
            human, tags = self.take_pending()
            bad = set(tags) - STRUCT_TAGS
            if bad:
                raise SchemaError(f"{self.path}:{line}: @{sorted(bad)[0]} belongs on a field")
            self.current = Struct(self.package, m.group(1), self.path, human, tags)
            self.structs.append(self.current)
            self.code = self.code[m.end():]
            return True
        if self.code and not re.match(r"(package|struct)\b", self.code):
            raise SchemaError(f"{self.path}:{line}: unexpected '{self.code[:40]}'")
        return False


def parse_lcm(path):
    """The structs of one .lcm file."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), open(path, encoding="utf-8").read(),
                  flags=re.S)
    r = _Reader(path)
    for n, raw in enumerate(text.splitlines(), start=1):
        code, slashes, comment = raw.partition("//")
        indent = len(raw) - len(raw.lstrip())
        if code.strip():
            r.code_line(code.strip(), comment.strip() if slashes else None, indent, n)
        elif slashes:
            r.comment_line(comment.strip(), indent, n)
        else:
            r.pending, r.last = [], None  # a blank line ends a comment block
    if r.current is not None or r.code.strip():
        raise SchemaError(f"{path}: unterminated struct or statement")
    return r.structs


def parse_all(paths):
    """Every struct of the given .lcm files, sorted by name."""
    structs = []
    for path in sorted(paths):
        structs += parse_lcm(path)
    return sorted(structs, key=lambda s: s.name)


SMALL_ARRAY_MAX = 16            # longer arrays go to the long-format points table
POINT_KEYS = ("utime", "tick", "seq")


def csv_columns(st):
    """Columns of a message's main table (tools/log2csv CHANNEL.csv): scalars, and arrays of up
    to SMALL_ARRAY_MAX elements expanded to name_0..name_k, in declaration order."""
    cols = []
    for f in st.fields:
        if f.length == 0:
            cols.append(f.name)
        elif f.length <= SMALL_ARRAY_MAX:
            cols += [f"{f.name}_{i}" for i in range(f.length)]
    return cols


def point_fields(st):
    """The arrays longer than SMALL_ARRAY_MAX (one common length): the points table."""
    large = [f for f in st.fields if f.length > SMALL_ARRAY_MAX]
    if len({f.length for f in large}) > 1:
        raise SchemaError(f"{st.path}: {st.name}: large arrays of different lengths are unsupported")
    return large


def point_keys(st):
    scalars = {f.name for f in st.fields if f.length == 0}
    return [k for k in POINT_KEYS if k in scalars]


def csv_point_columns(st):
    """Columns of a message's points table (CHANNEL_points.csv): keys, index i, the long arrays;
    empty when the message has none."""
    large = point_fields(st)
    return point_keys(st) + ["i"] + [f.name for f in large] if large else []
