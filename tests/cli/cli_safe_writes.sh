#!/usr/bin/env bash
# Safe writes (issue 19): outputs replace only a missing path or a regular file, never an input;
# the messages and codes of odd inputs; concurrent writers, a reader during a write and signals
# during a write leave a complete file or none, and no temporary.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

# Outputs replace only a missing path or a regular file, never the input, checked before any work.
targets=$work/targets
mkdir -p "$targets"
mkdir "$targets/d.stx" "$targets/d.png"
cp "$exemplar" "$targets/in.png"
ln "$targets/in.png" "$targets/in_link.png"
cp "$model" "$targets/model.stx"
cp "$model" "$targets/model.png" # a model under an image's name: render reads it by content
cp "$gabor_model" "$targets/gabor.stx"
printf 'kept\n' >"$targets/kept.png"
ln -s "$targets/kept.png" "$targets/link.png"
mkfifo "$targets/fifo.png"
expect_error "analyze onto a folder" 1 "$targets/d.stx" \
  "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$targets/d.stx"
if grep -q "Success" "$work/stderr"; then fail "analyze onto a folder" "says Success"; fi
expect_error "render onto a folder" 1 "a folder" \
  "$stochtex" render "$model" -o "$targets/d.png" "${size[@]}"
expect_error "render onto a symbolic link" 1 "$targets/link.png" \
  "$stochtex" render "$model" -o "$targets/link.png" "${size[@]}"
expect_error "render onto a FIFO" 1 "$targets/fifo.png" \
  "$stochtex" render "$model" -o "$targets/fifo.png" "${size[@]}"
# A device of our own, never /dev/null: a regression run as root would replace the machine's.
if mknod "$targets/null" c 1 3 2>/dev/null; then
  expect_error "analyze onto a device" 1 "$targets/null" \
    "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$targets/null"
  if [[ ! -c $targets/null ]]; then fail "analyze onto a device" "the device was replaced"; fi
fi
if [[ -L $targets/link.png && -p $targets/fifo.png && $(cat "$targets/kept.png") == kept ]]; then
  pass
else
  fail "refused targets are left as they were" "a link or FIFO was replaced"
fi
expect_error "analyze onto its input" 2 "$targets/in.png" \
  "$stochtex" analyze "$targets/in.png" "${fast[@]}" -o "$targets/in.png"
expect_error "analyze onto a hard link of its input" 2 "$targets/in_link.png" \
  "$stochtex" analyze "$targets/in.png" "${fast[@]}" -o "$targets/in_link.png"
expect_error "synth onto its input" 2 "$targets/in.png" \
  "$stochtex" synth "$targets/in.png" "${fast[@]}" -o "$targets/in.png" "${size[@]}"
expect_error "gaussian onto its input" 2 "$targets/in.png" \
  "$stochtex" gaussian "$targets/in.png" -o "$targets/in.png" "${size[@]}"
expect_error "render onto its model" 2 "$targets/model.png" \
  "$stochtex" render "$targets/model.png" -o "$targets/model.png" "${size[@]}"
expect_error "edit onto its model" 2 "$targets/gabor.stx" \
  "$stochtex" edit "$targets/gabor.stx" -o "$targets/gabor.stx" --scale 2
if cmp -s "$exemplar" "$targets/in.png" && cmp -s "$model" "$targets/model.png" &&
  cmp -s "$gabor_model" "$targets/gabor.stx"; then pass; else
  fail "inputs named as outputs are left as they were" "an input was overwritten"
fi
# Every input of every command is protected, not only the first (issue 35): mix's B and --mask,
# analyze's --map files, checked before any work.
cp "$exemplar" "$targets/b.png"
cp "$exemplar" "$targets/map.png"
expect_error "mix onto its exemplar B" 2 "$targets/b.png" \
  "$stochtex" mix "$exemplar" "$targets/b.png" -o "$targets/b.png" -p support=16 --steps 2
expect_error "mix onto its mask" 2 "$targets/map.png" \
  "$stochtex" mix "$exemplar" "$exemplar" --mask "$targets/map.png" -o "$targets/map.png"
expect_error "analyze onto its --map" 2 "$targets/map.png" \
  "$stochtex" analyze --map albedo="$targets/map.png" "${fast[@]}" -o "$targets/map.png"
if cmp -s "$exemplar" "$targets/b.png" && cmp -s "$exemplar" "$targets/map.png"; then pass; else
  fail "mix's and analyze's inputs named as outputs are kept" "an input was overwritten"
fi

# A FIFO (or any file that is not a regular one) as an input is refused before it is opened for
# reading, which would wait for a writer: each command ends at once (timeout: a hang fails).
for command in "analyze $targets/fifo.png ${fast[*]} -o $out/m.stx" \
  "gaussian $targets/fifo.png -o $out/g.png ${size[*]}" \
  "compare $exemplar $targets/fifo.png" \
  "mix $exemplar $targets/fifo.png -o $out/m.stx" \
  "mix $exemplar $exemplar --mask $targets/fifo.png -o $out/m.stx" \
  "analyze --map albedo=$targets/fifo.png ${fast[*]} -o $out/m.stx" \
  "info $targets/fifo.png" \
  "render $targets/fifo.png -o $out/r.png ${size[*]}" \
  "render-mesh $targets/fifo.png --model $model -o $out/r.png"; do
  # shellcheck disable=SC2086 # the words of the command
  expect_error "${command%% *} reading a FIFO" 1 "it is a FIFO" timeout 10 "$stochtex" $command
done

# An empty value is not the default (issue 35): refused in one sentence naming the option.
expect_error "render --seed ''" 2 "--seed" "$stochtex" render "$model" -o "$out/r.png" "${size[@]}" \
  --seed ''
expect_error "render --region ''" 2 "--region" \
  "$stochtex" render "$model" -o "$out/r.png" "${size[@]}" --region ''
expect_error "analyze --analysis-seed ''" 2 "--analysis-seed" \
  "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$out/m.stx" --analysis-seed ''
expect_error "edit --rotate ''" 2 "--rotate" \
  "$stochtex" edit "$gabor_model" -o "$out/e.stx" --rotate ''
expect_error "mix --steps ''" 2 "--steps" "$stochtex" mix "$exemplar" "$exemplar" -o "$out/m.stx" \
  --steps ''
expect_error "mix --ramp ''" 2 "--ramp" "$stochtex" mix "$exemplar" "$exemplar" -o "$out/m.stx" \
  --ramp ''

# A folder where the old fixed temporary name was does not matter any more.
mkdir "$targets/busy.png.tmp"
expect_ok "render beside a folder named like a temporary" \
  "$stochtex" render "$model" -o "$targets/busy.png" "${size[@]}" &&
  if [[ ! -s $targets/busy.png ]]; then fail "render beside a busy.png.tmp folder" "no file"; fi

# Wrong messages and codes.
python3 - "$inputs" <<'EOF'
import random, struct, sys, zlib
folder = sys.argv[1]
with open(folder + "/thin.pfm", "wb") as f:  # 1x4096 grey
    f.write(b"Pf\n1 4096\n-1.0\n" + b"".join(struct.pack("<f", (i % 7) / 7) for i in range(4096)))
random.seed(1)
with open(folder + "/huge.pfm", "wb") as f:  # finite values near the top of float's range
    f.write(b"Pf\n32 32\n-1.0\n"
            + b"".join(struct.pack("<f", random.choice((-3e38, 3e38))) for _ in range(1024)))
with open(folder + "/huge_rgb.pfm", "wb") as f:  # one channel near float's limit, one tiny
    f.write(b"PF\n32 32\n-1.0\n" + b"".join(
        struct.pack("<fff", random.choice((-3e38, 3e38)), random.random() * 1e-30, random.random())
        for _ in range(1024)))
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
rows = b"".join(b"\x00" + bytes(random.randrange(256) for _ in range(2 * 32)) for _ in range(32))
with open(folder + "/grey_alpha.png", "wb") as f:  # 32x32 grey + alpha
    f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 32, 32, 8, 4, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
EOF
expect_error "compare with a 1x4096 image" 1 "thin.pfm" \
  "$stochtex" compare "$exemplar" "$inputs/thin.pfm"
if grep -q "welch" "$work/stderr"; then fail "compare 1x4096" "names an internal function"; fi
expect_error "compare with a NaN image" 1 "nan.pfm" "$stochtex" compare "$exemplar" "$inputs/nan.pfm"
# Two 4096² colour images: about 3.1 GB for the measures (docs/design.md §9), refused before them.
expect_error "compare beyond the memory budget" 2 "4096x4096 image" \
  "$stochtex" compare "$inputs/ramp_4096.png" "$inputs/ramp_4096.png"
expect_error "lrp of values near float's limit is a data problem" 1 "huge.pfm" \
  "$stochtex" analyze "$inputs/huge.pfm" -m lrp -o "$out/huge.stx"
expect_error "gabor's singular colour transform names the file" 1 "huge_rgb.pfm" \
  "$stochtex" analyze "$inputs/huge_rgb.pfm" -m gabor -o "$out/huge.stx"
expect_ok "edit --list-groups with -o" "$stochtex" edit "$gabor_model" --list-groups \
  -o "$out/listed.stx" && if [[ -e $out/listed.stx ]]; then
  fail "edit --list-groups only lists" "it wrote the -o model"
  rm -f "$out/listed.stx"
else pass; fi
expect_ok "analyze a 2-channel exemplar" "$stochtex" analyze "$inputs/grey_alpha.png" "${fast[@]}" \
  -o "$models/grey_alpha.stx"
expect_error "render of 2 channels to .pfm fails before the render" 1 "PFM" \
  timeout 10 "$stochtex" render "$models/grey_alpha.stx" -o "$out/two.pfm" --size 8192x8192
expect_error "gaussian of 2 channels to .pfm" 1 "PFM" \
  "$stochtex" gaussian "$inputs/grey_alpha.png" -o "$out/two.pfm" "${size[@]}"

# Two concurrent writers of one output: each either succeeds or fails with one sentence, the file
# left is complete and is the one a successful writer wrote, and no temporary remains.
race=$work/race
mkdir -p "$race"
big=(--size 768x768)
"$stochtex" render "$model" -o "$race/seed3.png" "${big[@]}" --seed 3 2>/dev/null
"$stochtex" render "$model" -o "$race/seed4.png" "${big[@]}" --seed 4 2>/dev/null
for trial in 1 2 3; do
  "$stochtex" render "$model" -o "$race/out.png" "${big[@]}" --seed 3 2>"$race/err3" &
  pid3=$!
  "$stochtex" render "$model" -o "$race/out.png" "${big[@]}" --seed 4 2>"$race/err4" &
  pid4=$!
  wait $pid3
  status3=$?
  wait $pid4
  status4=$?
  matches=no
  if [[ $status3 -eq 0 ]] && cmp -s "$race/out.png" "$race/seed3.png"; then matches=yes; fi
  if [[ $status4 -eq 0 ]] && cmp -s "$race/out.png" "$race/seed4.png"; then matches=yes; fi
  clean=yes
  for seed in 3 4; do
    status_var=status$seed
    if [[ ${!status_var} -ne 0 ]] && ! grep -q '^stochtex: error: ' "$race/err$seed"; then
      clean=no
    fi
  done
  leftovers=$(find "$race" -name '*.tmp' | tr '\n' ' ')
  if [[ $matches == yes && $clean == yes && -z $leftovers ]]; then pass; else
    fail "two concurrent writers, trial $trial" \
      "exit $status3 and $status4, file of a successful writer: $matches, left: $leftovers"
  fi
  rm -f "$race/out.png"
done

# A reader during a write sees the old file or the new one, never a part.
cp "$race/seed3.png" "$race/out.png"
"$stochtex" render "$model" -o "$race/out.png" "${big[@]}" --seed 4 2>/dev/null &
writer=$!
partial=0
reads=0
while kill -0 $writer 2>/dev/null && ((reads++ < 5000)); do
  if ! cmp -s "$race/out.png" "$race/seed3.png" && ! cmp -s "$race/out.png" "$race/seed4.png"; then
    partial=$((partial + 1))
  fi
done
wait $writer
if [[ $? -eq 0 && $partial -eq 0 ]] && cmp -s "$race/out.png" "$race/seed4.png"; then pass; else
  fail "a reader during a write" "$partial read(s) saw neither the old nor the new file"
fi

# SIGINT or SIGTERM while the output is being written: no file and no temporary are left, and the
# exit status says the signal.
for signal in INT TERM; do
  rm -rf "$race/signal"
  mkdir "$race/signal"
  signal_during_write "SIG$signal during a write" $signal "$race/signal" '*.tmp' \
    "$stochtex" gaussian "$exemplar" -o "$race/signal/out.png" --size 2048x2048
done

summary
