#!/bin/sh
# Renders the looks library's thumbnails (data/looks/ID.png, embedded by app/src/looks.rs) with
# Rouge itself: the default head, the studio light rig, each look file. Run from the repository
# root after changing a look: sh data/looks/thumbnails.sh
set -eu
for id in natural evening editorial bold_lip; do
    cargo run --release -q -p rouge-app -- render --look "data/looks/$id.json" \
        --width 192 --height 192 --out "data/looks/$id.png"
done
