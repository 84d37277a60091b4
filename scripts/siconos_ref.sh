# Sourced (not run) by the scripts that read Siconos's SliderCrank example
# output: sets refdir (the folder, $FOURBAR_SICONOS_REF_DIR or the clone's
# git-ignored external/siconos_slider_crank) and ref (the .ref file), and
# stops the script, saying where to fetch it, when the file is not there.
refdir=${FOURBAR_SICONOS_REF_DIR:-external/siconos_slider_crank}
ref=$refdir/SliderCrankMoreauJeanCombinedProjectionOSI.ref
[ -r "$ref" ] || { echo "no $ref: see docs/models.md for where to fetch it" >&2; exit 1; }
