/* Rule 1: a file of no unit and not of the lifecycle. */
int stray(void)
{
    return 0;
}
