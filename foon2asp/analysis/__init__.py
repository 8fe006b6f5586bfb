"""Questions over trees and FOONs: checking tree files, comparing methods, consolidating candidates, queries."""
