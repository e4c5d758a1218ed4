/* Unit a.
 *
 * Owns:   unit_a
 * Files:  unit_a.c */
typedef struct unit_a {
    int n;
} unit_a;
