/* depgraph_finds_cycle: the other half of the cycle. */
int lep_depgraph_a(int n);
int lep_depgraph_b(int n);

int lep_depgraph_b(int n)
{
    return n > 0 ? lep_depgraph_a(n - 1) : 1;
}
