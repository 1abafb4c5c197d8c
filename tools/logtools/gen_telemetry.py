#!/usr/bin/python3
"""Emit, at build time from interfaces/*.lcm, the telemetry plumbing (interfaces/README.md):

  --core OUT.hpp   for every message tagged @core TYPE: TYPE, a plain struct with one member per
                   field (the stamps utime and tick excepted) for the algorithm core, which has no
                   LCM dependency. @bits fields become one bool per constant, @enum fields their
                   enum type, @default sets an initial value.
  --fill OUT.hpp   for every message tagged @fill (or @core): reentry::fill(msg&, const Sources&...), which
                   copies each field (stamps excepted: reentry::stamp) from the one source struct
                   that has a member of its name or @from path. The build fails when no source or
                   more than one has it, on a narrowing copy, when an enum source's values differ
                   from the field's FIELD_* constants, or when an enum source has no constants.

usage: gen_telemetry.py --core OUT.hpp --fill OUT.hpp file.lcm...
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lcm_schema import INTEGERS, STAMPS, SchemaError, parse_all  # noqa: E402

CPP_TYPES = {"int8_t": "std::int8_t", "int16_t": "std::int16_t", "int32_t": "std::int32_t",
             "int64_t": "std::int64_t", "byte": "std::uint8_t", "float": "float", "double": "double",
             "boolean": "bool"}
ZERO = {"float": "0.0f", "double": "0.0", "boolean": "false"}
TYPE_BITS = {"int8_t": 8, "int16_t": 16, "int32_t": 32, "int64_t": 64, "byte": 8}


def enumerator(const_name, prefix):
    """PHASE_INITIAL_DESCENT (prefix PHASE_) -> kInitialDescent, the C++ enumerator it names."""
    return "k" + "".join(w.capitalize() for w in const_name[len(prefix):].lower().split("_"))


def bit_member(const_name, prefix):
    """FLAGS_FINAL_REVERSAL_DONE (prefix FLAGS_) -> final_reversal_done, the bool it packs."""
    return const_name[len(prefix):].lower()


def check_struct(st):
    """The tags of one message are consistent; raises SchemaError naming the file and field."""
    core = "core" in st.tags
    for f in st.fields:
        where = f"{st.path}:{f.line}: {st.name}.{f.name}"
        tags = set(f.tags)
        if f.name in STAMPS and tags:
            raise SchemaError(f"{where}: the stamps utime and tick take no tags")
        if core and tags & {"from", "value"}:
            raise SchemaError(f"{where}: @from / @value do not apply to a @core message (its struct is generated)")
        if not core and tags & {"default", "enum"}:
            raise SchemaError(f"{where}: @default / @enum need @core on the message")
        if ("from" in tags) + ("value" in tags) + ("bits" in tags) > 1:
            raise SchemaError(f"{where}: @from, @value and @bits exclude each other")
        if f.type == "string" or (f.type not in CPP_TYPES):
            raise SchemaError(f"{where}: type {f.type} is not supported by the telemetry generator")
        if ("bits" in tags or "enum" in tags) and (f.type not in INTEGERS or f.length):
            raise SchemaError(f"{where}: @bits / @enum need an integer scalar field")
        if "bits" in tags:
            check_bits(st, f, where)
        if "enum" in tags and not st.consts_of(f.name):
            raise SchemaError(f"{where}: @enum needs the values as constants {f.name.upper()}_*")


def check_bits(st, f, where):
    masks = st.consts_of(f.name)
    if not masks:
        raise SchemaError(f"{where}: @bits needs one constant {f.name.upper()}_<NAME> = mask per bit")
    seen = 0
    for c in masks:
        v = int(c.value, 0)
        if v <= 0 or v & (v - 1) or v >= 1 << (TYPE_BITS[f.type] - 1):
            raise SchemaError(f"{where}: {c.name} = {c.value} is not one bit of a {f.type} (sign bit excluded)")
        if seen & v:
            raise SchemaError(f"{where}: {c.name} = {c.value} repeats a bit")
        seen |= v


def core_members(st, f):
    """Declarations of the @core struct's member(s) for one field."""
    comment = f"  // {f.comment}" if f.comment else ""
    if "bits" in f.tags:
        prefix = f.name.upper() + "_"
        return [f"  bool {bit_member(c.name, prefix)} = false;  // {f.name} & {c.name}"
                + (f": {c.comment}" if c.comment else "") for c in st.consts_of(f.name)]
    if "enum" in f.tags:
        t = f.tags["enum"][0]
        init = f" = {f.tags['default'][0]}" if "default" in f.tags else "{}"
        return [f"  {t} {f.name}{init};{comment}"]
    t = CPP_TYPES[f.type]
    if f.length:
        return [f"  {t} {f.name}[{f.length}] = {{}};{comment}"]
    init = f.tags["default"][0] if "default" in f.tags else ZERO.get(f.type, "0")
    return [f"  {t} {f.name} = {init};{comment}"]


def emit_block(w, head, st, lines_of, tail):
    """head, the lines of every field but the stamps, tail."""
    w(head)
    for f in st.fields:
        if f.name not in STAMPS:
            w("\n".join(lines_of(st, f)) + "\n")
    w(tail)


def emit_core(structs, out):
    w = out.write
    w("// Generated by tools/logtools/gen_telemetry.py from interfaces/*.lcm (the messages tagged @core).\n"
      "// Do not edit: change the .lcm file. Plain data for the algorithm core: no LCM dependency.\n"
      "#pragma once\n\n#include <cstdint>\n")
    headers = sorted({f.tags["enum"][1] for st in structs for f in st.fields if "enum" in f.tags})
    for h in headers:
        w(f'#include "{h}"\n')
    for st in structs:
        qual = st.tags["core"][0].split("::")
        ns, name = "::".join(qual[:-1]), qual[-1]
        w(f"\n{'namespace ' + ns + ' {' if ns else ''}\n\n")
        doc = f"/// {st.comment}\n" if st.comment else ""
        doc += (f"/// The fields of {st.name} ({os.path.basename(st.path)}) but its stamps utime and tick;\n"
                f"/// reentry::fill(msg, this) copies them into the message.\n")
        emit_block(w, f"{doc}struct {name} {{\n", st, core_members, "};\n")
        w(f"\n}}  // namespace {ns}\n" if ns else "")


def probe_path(f):
    return f.tags["from"][0] if "from" in f.tags else f.name


def fill_field(st, f):
    """The statements of fill() that set one field."""
    ns, lit = f"p_{st.name}", f"{st.name}.{f.name}"
    if "value" in f.tags:
        return [f"  m.{f.name} = {f.tags['value'][0]};"]
    if "bits" in f.tags:
        return fill_bits(st, f)
    probe, path = f"{ns}::{f.name}", probe_path(f)
    lines = [f"  static_assert(fill_support::sources_with<{probe}, S...> == 1,",
             f'                "{lit}: exactly one source must have a member {path}");']
    value = f"fill_support::value_t<{probe}, S...>"
    if st.consts_of(f.name):
        lines.append(f"  {ns}::check_{f.name}<{value}>();")
    else:
        lines += [f"  static_assert(!std::is_enum_v<{value}>,",
                  f'                "{lit}: its source is an enum: declare its values as {f.name.upper()}_* constants");']
    if not f.length:
        lines += [f"  static_assert(!fill_support::narrows<decltype(m.{f.name}), {value}>,",
                  f'                "{lit}: the type of {path} narrows into the field\'s: convert it in the source");']
    if f.length:
        lines.append(f"  fill_support::copy_array(m.{f.name}, fill_support::pick<{probe}>(src...));")
    else:
        lines.append(f"  m.{f.name} = fill_support::convert<decltype(m.{f.name})>(fill_support::pick<{probe}>(src...));")
    return lines


def fill_bits(st, f):
    ns, prefix = f"p_{st.name}", f.name.upper() + "_"
    lines, terms = [], []
    for c in st.consts_of(f.name):
        member = bit_member(c.name, prefix)
        probe = f"{ns}::{member}"
        lines += [f"  static_assert(fill_support::sources_with<{probe}, S...> == 1 &&",
                  f"                    std::is_same_v<fill_support::value_t<{probe}, S...>, bool>,",
                  f'                "{st.name}.{f.name}: {c.name} needs exactly one source with a bool {member}");']
        terms.append(f"(fill_support::pick<{probe}>(src...) ? {st.name}::{c.name} : 0)")
    joined = " |\n      ".join(terms)
    lines.append(f"  m.{f.name} = static_cast<{CPP_TYPES[f.type]}>(\n      {joined});")
    return lines


def emit_probes(st, w):
    w(f"namespace p_{st.name} {{\n")
    for f in st.fields:
        if f.name in STAMPS or "value" in f.tags:
            continue
        if "bits" in f.tags:
            prefix = f.name.upper() + "_"
            for c in st.consts_of(f.name):
                m = bit_member(c.name, prefix)
                w(f"REENTRY_FILL_PROBE({m}, {m});\n")
            continue
        w(f"REENTRY_FILL_PROBE({f.name}, {probe_path(f)});\n")
        consts = st.consts_of(f.name)
        if consts:
            prefix = f.name.upper() + "_"
            w(f"// The values of {f.name}: each {prefix}* constant is the enumerator k<Name> of the source enum.\n")
            w("template <class E>\nconstexpr void check_" + f.name + "() {\n  if constexpr (std::is_enum_v<E>) {\n")
            for c in consts:
                e = enumerator(c.name, prefix)
                w(f"    static_assert(static_cast<long long>(E::{e}) == {st.name}::{c.name},\n"
                  f'                  "{st.name}.{f.name}: {c.name} differs from the source enum\'s {e}");\n')
            w("  }\n}\n")
    w(f"}}  // namespace p_{st.name}\n\n")


def emit_fill(structs, out):
    w = out.write
    w("// Generated by tools/logtools/gen_telemetry.py from interfaces/*.lcm (the messages tagged @fill).\n"
      "// Do not edit: change the .lcm file. See interfaces/README.md.\n#pragma once\n\n"
      "#include <type_traits>\n\n#include <reentry/fill_support.hpp>\n")
    for st in structs:
        w(f"#include <{st.package.replace('.', '/')}/{st.name}.hpp>\n")
    w("\nnamespace reentry {\n\n")
    for st in structs:
        emit_probes(st, w)
        head = (f"/// Every field of {st.name} but utime and tick, each from the one source that has it\n"
                f"/// ({os.path.basename(st.path)}).\ntemplate <class... S>\n"
                f"void fill({st.name}& m, const S&... src) {{\n")
        emit_block(w, head, st, fill_field, "}\n\n")
    w("}  // namespace reentry\n")


def write(path, emit, structs):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        emit(structs, f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--core", required=True)
    ap.add_argument("--fill", required=True)
    ap.add_argument("lcm", nargs="+")
    a = ap.parse_args()
    try:
        structs = parse_all(a.lcm)
        for st in structs:
            if {"core", "fill"} & set(st.tags):
                check_struct(st)
    except SchemaError as e:
        sys.exit(f"gen_telemetry: {e}")
    for st in structs:
        if "core" in st.tags and not re.match(r"^(\w+::)*\w+$", st.tags["core"][0]):
            sys.exit(f"gen_telemetry: {st.path}: @core needs a C++ type name, not '{st.tags['core'][0]}'")
    write(a.core, emit_core, [s for s in structs if "core" in s.tags])
    write(a.fill, emit_fill, [s for s in structs if {"core", "fill"} & set(s.tags)])


if __name__ == "__main__":
    main()
