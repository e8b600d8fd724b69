//! Helpers shared by the unit tests of several modules.

/// A sink whose reader has gone away: every write fails with a broken pipe, as stdout does when
/// `symdyn derive … | head` has read enough.
pub(crate) struct Closed;

impl std::io::Write for Closed {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::ErrorKind::BrokenPipe.into())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}
