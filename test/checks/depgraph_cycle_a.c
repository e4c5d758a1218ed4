/* depgraph_finds_cycle: one half of a cycle between two files (never linked
 * into a program; the check must name this cycle). */
int lep_depgraph_b(int n);
int lep_depgraph_a(int n);

int lep_depgraph_a(int n)
{
    return n > 0 ? lep_depgraph_b(n - 1) : 0;
}
