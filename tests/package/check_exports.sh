#!/bin/bash
# What libbodyfmt.so exports (libbodyfmt/include/bodyfmt/export.h): the public API, and none of
# the internals. Fails when
#  - a symbol of an internal namespace is exported: bodyfmt::detail (the loader), bodyfmt::yaml
#    (the YAML tree), bodyfmt::mesh (the mesh readers), an anonymous namespace, or a
#    bodyfmt::text function other than the public quoting and UTF-8 ones (bodyfmt/text.h);
#  - a bodyfmt:: name is exported that no public header declares (a function of src/ left
#    visible: the library was built without hidden visibility, or a source file exports it);
#  - a function of the public API is missing (the library was built without the export pragmas);
#  - a public header opens a namespace outside its export pragmas (bodyfmt/export.h), so that
#    what it declares would be hidden from other projects.
# Usage: check_exports.sh LIBBODYFMT_SO PUBLIC_INCLUDE_DIR
set -u
library=$1
include_dir=$2
status=0

symbols=$(nm -DC --defined-only "$library" | cut -d' ' -f3-)
if [ -z "$symbols" ]; then
  echo "FAIL: nm found no exported symbols in $library"
  exit 1
fi

internal=$(grep -E 'bodyfmt::(detail|yaml|mesh)::|\(anonymous namespace\)' <<<"$symbols")
text_private=$(grep -E 'bodyfmt::text::' <<<"$symbols" |
               grep -vE '^bodyfmt::text::(json_quote|yaml_quote|yaml_escape|xml_escape|xml_comment_text|is_xml_text|utf8_sequence|is_utf8|uri_path_encode)(\[abi:cxx11\])?\(')
if [ -n "$internal$text_private" ]; then
  echo "FAIL: $library exports internals ($(printf '%s\n%s' "$internal" "$text_private" | grep -c .) symbols), e.g.:"
  printf '%s\n%s\n' "$internal" "$text_private" | grep . | head -10
  status=1
fi

# The first name after bodyfmt:: (or bodyfmt::text::) of every exported symbol, looked up as a
# word in the public headers.
undeclared=$(sed -E 's/^(vtable|typeinfo|typeinfo name|VTT) for //' <<<"$symbols" | grep -E '^bodyfmt::' |
             sed -E 's/\[abi:cxx11\]//g; s/^bodyfmt::(text::)?//; s/^(operator[^(]*|[A-Za-z_0-9]+).*/\1/' | sort -u |
             while read -r name; do
               grep -qwF -- "$name" "$include_dir"/bodyfmt/*.h || echo "bodyfmt::$name"
             done)
if [ -n "$undeclared" ]; then
  echo "FAIL: $library exports $(grep -c . <<<"$undeclared") names no public header declares, e.g.:"
  head -10 <<<"$undeclared"
  status=1
fi

# Names as nm -C prints them; a function returning std::string carries the [abi:cxx11] tag.
for wanted in bodyfmt::load_body bodyfmt::compute_derived bodyfmt::format_diagnostic bodyfmt::report_rule \
              bodyfmt::tessellate bodyfmt::FileName::str bodyfmt::read_yaml_file bodyfmt::parse_yaml_text \
              bodyfmt::YamlNode::entries bodyfmt::YamlReader::number bodyfmt::did_you_mean \
              bodyfmt::text::json_quote bodyfmt::text::xml_escape 'vtable for bodyfmt::CollectingSink'; do
  if ! grep -qE "^${wanted}(\[abi:cxx11\])?(\(|$)" <<<"$symbols"; then
    echo "FAIL: $library does not export $wanted"
    status=1
  fi
done

for header in "$include_dir"/bodyfmt/*.h; do
  # (Namespaces nested in such a block, e.g. bodyfmt::text, are inside it.)
  bad=$(awk '/^#pragma GCC visibility push\(default\)/ { inside = 1 } /^#pragma GCC visibility pop/ { inside = 0 }
             /^namespace ([^ ]+ )?bodyfmt/ && !inside { print FNR ": " $0 }' "$header")
  if [ -n "$bad" ]; then
    echo "FAIL: $header opens a namespace outside '#pragma GCC visibility push(default)' (its declarations would not be exported):"
    echo "$bad"
    status=1
  fi
done

[ $status -eq 0 ] && echo "ok: $library exports $(wc -l <<<"$symbols") symbols, none of them internal"
exit $status
