#!/usr/bin/env bash
# Every option that `ssrcl trace|batch|bench|devices --help` lists must be named in docs/cli.md,
# and every option cli.md names must be one of theirs (or the top level's), so the page can
# neither miss an option nor keep one that is gone.
#   check_cli_docs.sh SSRCL CLI_MD
set -euo pipefail
ssrcl=$1 doc=$2
[[ -r $doc ]] || { echo "cannot read $doc"; exit 1; }

# Option names at the start of a help line: "  -o,--output TEXT ..." gives -o and --output.
options_of() {
  "$ssrcl" "$@" --help | sed -nE 's/^ +(--?[A-Za-z0-9][-A-Za-z0-9]*(,--?[A-Za-z0-9][-A-Za-z0-9]*)*).*/\1/p' | tr ',' '\n'
}

status=0 all=$(options_of)
for command in trace batch bench devices; do
  listed=$(options_of "$command")
  [[ -n $listed ]] || { echo "ssrcl $command --help lists no option"; exit 1; }
  all+=$'\n'$listed
  for option in $listed; do
    # The name as a whole word: --thickness must not be found only inside --thickness-model.
    if ! grep -qE -- "(^|[^-A-Za-z0-9])${option}([^-A-Za-z0-9]|$)" "$doc"; then
      echo "docs/cli.md does not mention ssrcl $command option $option"
      status=1
    fi
  done
done

# The other way: options cli.md names that no command has (a renamed or removed option).
for option in $(grep -oE -- '(^|[^-A-Za-z0-9])--[A-Za-z0-9][-A-Za-z0-9]*' "$doc" | grep -oE -- '--.*' | sort -u); do
  if ! grep -qxF -- "$option" <<<"$all"; then
    echo "docs/cli.md names $option, which no ssrcl command has"
    status=1
  fi
done
exit $status
