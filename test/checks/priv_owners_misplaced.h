/* priv_owners_finds_misplaced: a private header whose map is wrong on
 * purpose (never included): lep_depgraph_a is defined in depgraph_cycle_a.c,
 * not in the section it sits in. */
/* depgraph_cycle_b.c */
int lep_depgraph_b(int n);
int lep_depgraph_a(int n);
