# The listing references, reference/outputs/NAME.txt (sourced, not run;
# from the project root): the default listing of each case deck NAME, and
# NAME_all, the full listing of a deck with a `PRINT ALL` card added at its
# end. Each at --rtol 1.0E-7 (dev/regenerate_references.sh says why).
# Used by test/scripts/listing_references.sh, dev/regenerate_references.sh
# and dev/listing_robustness.sh.
#   reference_listing EXE NAME   the listing of reference NAME on standard output
REFERENCE_LISTINGS="case6-1 case6-2 case6-5 nbdl15g nbdl12g hybrid3_flexion rear8g case6-2_all"
reference_listing() {
    case $2 in
        *_all) { cat "input/${2%_all}.inp"; echo "PRINT     ALL"; } | "$1" --no-h5 --rtol 1.0E-7 ;;
        *) "$1" --no-h5 --rtol 1.0E-7 < "input/$2.inp" ;;
    esac
}
