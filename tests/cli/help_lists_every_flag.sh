#!/usr/bin/env bash
# For every command of `horopter`: the flags its --help lists are exactly the
# flags it reads. Usage: help_lists_every_flag.sh HOROPTER
#
# Listed: the option lines of `horopter CMD --help` ("  --flag V  help" or
# "  -o, --out DIR  help"; prose never starts a line with "  -").
# Read: HOROPTER_LIST_FLAGS=1 makes the command print every flag it asked
# its argument list for (engine/cli/args.hpp) and exit before any work.
# A flag in one list and not the other fails the test, naming both.
set -euo pipefail
horopter="$1"

# The commands, from the tool's own usage ("  name   what it does").
commands=$("$horopter" --help | sed -n '/^Commands:/,/^$/p' | sed -n 's/^  \([a-z][a-z-]*\) .*/\1/p')
[ -n "$commands" ] || { echo "no commands found in horopter --help"; exit 1; }

failed=0
count=0
for cmd in $commands; do
  listed=$("$horopter" "$cmd" --help |
    sed -n 's/^  \(-[a-zA-Z], \)\{0,1\}\(--\{0,1\}[a-zA-Z][a-z0-9-]*\)\( [^ ]*\)\{0,1\}\(  .*\)\{0,1\}$/\1\2/p' |
    sed 's/, /\n/' | sort -u)
  # (A command that ignored the variable would start its work: the timeout ends it.)
  errors=$(mktemp)
  read=$(HOROPTER_LIST_FLAGS=1 timeout 20 "$horopter" "$cmd" 2>"$errors" | sort -u || true)
  if [ -z "$read" ]; then
    # A malformed table (a default out of range...) stops every run: its error says which.
    echo "$cmd: HOROPTER_LIST_FLAGS printed no flag: $(cat "$errors")"
    rm -f "$errors"
    failed=1
    continue
  fi
  rm -f "$errors"
  only_listed=$(comm -23 <(echo "$listed") <(echo "$read"))
  only_read=$(comm -13 <(echo "$listed") <(echo "$read"))
  if [ -n "$only_listed" ]; then
    echo "$cmd: --help lists flags the command does not read:" $only_listed
    failed=1
  fi
  if [ -n "$only_read" ]; then
    echo "$cmd: the command reads flags --help does not list:" $only_read
    failed=1
  fi
  count=$((count + 1))
  echo "$cmd: $(echo "$read" | wc -l) flags, listed and read alike"
done
echo "$count commands checked"
exit $failed
