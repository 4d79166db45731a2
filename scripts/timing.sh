# Sourced by scripts/test.sh and scripts/sanitize.sh: `phase NAME` prints how long the script spent
# since its start or its previous phase, and appends the line to $STOCHTEX_TIMES when it is set
# (.ci/run prints that file at its end: the time of each tier).
phase_start=$SECONDS
phase() {
  local line
  line=$(printf '%-34s %5d s' "$1" $((SECONDS - phase_start)))
  echo "stochtex: $line" >&2
  if [[ -n ${STOCHTEX_TIMES:-} ]]; then echo "$line" >>"$STOCHTEX_TIMES"; fi
  phase_start=$SECONDS
}
