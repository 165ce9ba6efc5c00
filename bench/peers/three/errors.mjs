// The bench's one error type: a message for the person running it and the exit code
// (1 usage, 2 a missing prerequisite, 3 the wrong renderer or a failed measurement).
export class PeerError extends Error {
  constructor(message, exitCode) {
    super(message);
    this.exitCode = exitCode;
  }
}
