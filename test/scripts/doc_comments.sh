#!/bin/sh
# Every dummy argument of a public procedure in src/ has a trailing !!
# comment of its own (minpack's style, docs/architecture.md), checked by
# dev/check_doc_comments.py; first the checker itself on a small module
# whose undocumented dummies are known.
# This check runs no executable: HHNECK is not needed.
HHNECK=${HHNECK:-none}
. test/scripts/lib/checks.sh

# The checker on a module with known gaps: several dummies on one line (both
# listed, although the line has a comment), a continuation line, a
# procedure dummy, a function result (not a dummy), `me` (exempt), a
# private procedure (not checked) and a type-bound one.
cat > "$tmp/known.f90" <<'EOF'
module known
    implicit none
    private
    public :: pair, f, t_t
    type :: t_t
    contains
        procedure :: bound => t_bound
    end type t_t
contains
    subroutine pair(a, b, &
                    c, g)
        real, intent(in) :: a, b   !! one comment for two
        real, intent(in) :: c(:, &
                              :)   !! on the continuation line
        procedure(f) :: g
    end subroutine pair
    real function f(x) result(r)
        real, intent(in) :: x   !! documented
        r = x
    end function f
    subroutine t_bound(me, n)
        class(t_t), intent(in) :: me
        integer, intent(in) :: n
    end subroutine t_bound
    subroutine hidden(k)
        integer, intent(in) :: k
    end subroutine hidden
end module known
EOF
python3 dev/check_doc_comments.py "$tmp/known.f90" > "$tmp/known.out" 2> "$tmp/known.err"
rc=$?
cat > "$tmp/known.expected" <<EOF
$tmp/known.f90:12 pair a (shares its line)
$tmp/known.f90:12 pair b (shares its line)
$tmp/known.f90:15 pair g
$tmp/known.f90:23 t_bound n
EOF
check "the checker exits 1 on a module with undocumented dummies (got $rc)" [ "$rc" -eq 1 ]
check "it lists exactly the 4 undocumented dummies, as file:line procedure argument" \
    cmp -s "$tmp/known.out" "$tmp/known.expected"
check "it checks 6 dummies of 3 public procedures (not the result, me, or the private one)" \
    grep -q '^6 dummy arguments of 3 public procedures in 1 files checked; 4 without' "$tmp/known.err"
check "a --skip that names no file is an error (exit 2)" \
    sh -c "python3 dev/check_doc_comments.py --skip '$tmp/none.f90' '$tmp/known.f90' > /dev/null 2>&1; [ \$? -eq 2 ]"

# The source tree, all of it.
python3 dev/check_doc_comments.py \
    src > "$tmp/src.out" 2> "$tmp/src.err"
rc=$?
summary=$(tail -n 1 "$tmp/src.err")
check "every dummy argument of a public procedure in src/ has a trailing !! comment ($summary)" [ "$rc" -eq 0 ]
if [ "$rc" -ne 0 ]; then
    head -n 20 "$tmp/src.out"
fi
finish
