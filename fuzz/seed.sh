#!/bin/sh
# Seeds the fuzz corpora from the repository: every deck (examples,
# verification cases, test decks, bad decks), every gmsh test mesh, and
# restart points written by running two example decks. Run from fuzz/.
set -e
root=$(cd .. && pwd)
mkdir -p corpus/deck corpus/gmsh corpus/restart
find "$root/examples" "$root/verification/cases" "$root/tests/decks" \
     "$root/lang/tests/decks" "$root/lang/tests/bad_decks" -name '*.ctc' \
     -exec cp {} corpus/deck/ \;
find "$root/engine/tests/data" "$root/lang/tests" -name '*.msh' \
     -exec cp {} corpus/gmsh/ \;
tmp=$(mktemp -d)
for deck in contact_patch cylinder_on_block; do
  (cd "$root" && cargo run -q -- run "examples/$deck.ctc" -o "$tmp/$deck" -q) || true
  [ -f "$tmp/$deck/restart.bin" ] && cp "$tmp/$deck/restart.bin" "corpus/restart/$deck.bin"
done
rm -rf "$tmp"
ls corpus/*/ | wc -l
